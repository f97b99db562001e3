#pragma once
// What the three inputs of `mirror-eval aam` share (aam_eval.hpp): one peer's scores over a run,
// the report's rows, the frames of a folder, our runner and dlib's predictor run and timed on one
// frame. Internal to mirror-eval aam.

#include "aam_eval.hpp"
#include "aam_scoring.hpp"
#include "error_stats.hpp"
#include "head_fit_runner.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mirror_eval::aam_report {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
inline constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

/// A bad argument: exit code 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

double msSince(Clock::time_point t0);

/// The mean, or NaN (printed "nan") when there is nothing to average: a score that was not made
/// is not a zero.
inline double meanOrNan(const std::vector<double>& v)
{
    return v.empty() ? kNan : meanOf(v);
}
inline double p90OrNan(const ErrorStats& e)
{
    return e.values.empty() ? kNan : e.percentile(0.9);
}

/// What one peer scored over a run.
struct PeerScores {
    /// Implicit, so that a row is made from its name alone: PeerScores ours{"aam fit"}.
    PeerScores(std::string rowName = "") : name(std::move(rowName)) {}

    std::string name;
    ErrorStats nme{"nme", {}}, nmeAll{"nme_all", {}};
    std::vector<double> ms, iterations;
    long lost = 0;
    std::vector<double> jaw, jawTruth;  ///< its jaw value and the truth's, per scored frame
    ErrorStats yaw{"yaw", {}}, pitch{"pitch", {}}, roll{"roll", {}};
    std::vector<double> animationSquares;
    bool hasPose = false;

    void addNme(const std::optional<FrameNme>& f)
    {
        if (f) {
            nme.values.push_back(f->inner);
            nmeAll.values.push_back(f->all);
        }
    }
    double jawCorrelation() const { return pearson(jaw, jawTruth); }
    double animationRmse() const
    {
        return animationSquares.empty() ? kNan : std::sqrt(meanOf(animationSquares));
    }
};

/// `v` in `format`, or "nan".
std::string number(double v, const char* format = "%.4f");
void printHeader(std::FILE* out);
void printRow(std::FILE* out, const PeerScores& p, int points);

/// The frames of a folder (PNG, JPEG) in file-name order; a UsageError when there are none.
std::vector<fs::path> framesIn(const std::string& dir);
/// The frames from options.start, at most options.maxFrames of them.
std::vector<fs::path> slice(std::vector<fs::path> frames, const AamEvalOptions& o);
cv::Mat readGrey(const fs::path& path);

/// The runner --fitter names; an unknown name is a UsageError.
std::unique_ptr<HeadFitRunner> makeRunner(const AamEvalOptions& o, DlibPeer& dlib);
/// Says which runner is ours, and loudly when it is the placeholder.
void printFitterLine(std::FILE* out, const HeadFitRunner& runner);
/// Our rows' name: "mean shape baseline*" for the placeholder, "aam fit" otherwise.
std::string oursName(const HeadFitRunner& runner);

/// Our runner on one frame, timed; none (counted lost, the runner restarted) when it let go.
std::optional<HeadFit> runOurs(HeadFitRunner& runner, const cv::Mat& grey, const FaceBoxPx& box,
                               PeerScores& ours);
/// dlib's 68 points on one frame, timed.
std::vector<Eigen::Vector2d> runDlib(DlibPeer& dlib, const cv::Mat& grey, const FaceBoxPx& box,
                                     PeerScores& peer);

int runSyntheticEval(const AamEvalOptions& o, std::FILE* out);
int runImmEval(const AamEvalOptions& o, std::FILE* out);

}  // namespace mirror_eval::aam_report
