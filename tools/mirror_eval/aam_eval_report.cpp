// What mirror-eval aam's three inputs share (aam_eval_report.hpp).
#include "aam_eval_report.hpp"

#include <algorithm>
#include <opencv2/imgcodecs.hpp>

namespace mirror_eval::aam_report {

double msSince(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string number(double v, const char* format)
{
    if (std::isnan(v))
        return "nan";
    char text[32];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

void printHeader(std::FILE* out)
{
    std::fprintf(out, "%-28s %6s %8s %8s %8s %6s %8s %6s %9s %5s\n", "peer", "frames", "nme",
                 "nme_p90", "nme_all", "points", "jaw_corr", "iters", "ms/frame", "lost");
}

void printRow(std::FILE* out, const PeerScores& p, int points)
{
    std::fprintf(out, "%-28s %6zu %8s %8s %8s %6d %8s %6s %9s %5ld\n", p.name.c_str(),
                 p.nme.values.size(), number(meanOrNan(p.nme.values)).c_str(),
                 number(p90OrNan(p.nme)).c_str(), number(meanOrNan(p.nmeAll.values)).c_str(),
                 points, number(p.jawCorrelation(), "%.3f").c_str(),
                 p.iterations.empty() ? "-" : number(meanOrNan(p.iterations), "%.2f").c_str(),
                 number(meanOrNan(p.ms), "%.2f").c_str(), p.lost);
}

/// The frames of a folder (PNG, JPEG) in file-name order.
std::vector<fs::path> framesIn(const std::string& dir)
{
    if (!fs::is_directory(dir))
        throw UsageError(dir + ": not a folder");
    std::vector<fs::path> frames;
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string ext = e.path().extension().string();
        if (ext == ".png" || ext == ".jpg" || ext == ".jpeg")
            frames.push_back(e.path());
    }
    std::sort(frames.begin(), frames.end());
    if (frames.empty())
        throw UsageError(dir + ": no .png or .jpg frames");
    return frames;
}

std::vector<fs::path> slice(std::vector<fs::path> frames, const AamEvalOptions& o)
{
    if (o.start >= static_cast<int>(frames.size()))
        throw UsageError("--start " + std::to_string(o.start) + ": the sequence has only " +
                         std::to_string(frames.size()) + " frames");
    frames.erase(frames.begin(), frames.begin() + o.start);
    if (o.maxFrames > 0 && static_cast<int>(frames.size()) > o.maxFrames)
        frames.resize(static_cast<std::size_t>(o.maxFrames));
    return frames;
}

cv::Mat readGrey(const fs::path& path)
{
    cv::Mat grey = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    if (grey.empty())
        throw std::runtime_error(path.string() + ": cannot read the frame");
    return grey;
}

/// Our runner on one frame: timed, its points, its jaw drop against `jawTruth` when both exist.
std::optional<HeadFit> runOurs(HeadFitRunner& runner, const cv::Mat& grey, const FaceBoxPx& box,
                               PeerScores& ours)
{
    const auto t0 = Clock::now();
    HeadFit fit = runner.fit(grey, box);
    ours.ms.push_back(msSince(t0));
    if (!runner.placeholder())
        ours.iterations.push_back(fit.iterations);
    if (!fit.held) {
        ++ours.lost;
        runner.restart();
        return std::nullopt;
    }
    return fit;
}

/// dlib's 68 points on one frame, timed.
std::vector<Eigen::Vector2d> runDlib(DlibPeer& dlib, const cv::Mat& grey, const FaceBoxPx& box,
                                     PeerScores& peer)
{
    const auto t0 = Clock::now();
    std::vector<Eigen::Vector2d> points = dlib.landmarks(grey, box);
    peer.ms.push_back(msSince(t0));
    return points;
}

void printFitterLine(std::FILE* out, const HeadFitRunner& runner)
{
    std::fprintf(out, "ours: %s\n", runner.label().c_str());
    if (runner.placeholder())
        std::fprintf(out,
                     "  PLACEHOLDER: vision's AAM fit is not wired yet; its rows are a reference, "
                     "not the fit (no pose, no expression, no iterations)\n");
}

std::string oursName(const HeadFitRunner& runner)
{
    return runner.placeholder() ? "mean shape baseline*" : "aam fit";
}

std::unique_ptr<HeadFitRunner> makeRunner(const AamEvalOptions& o, DlibPeer& dlib)
{
    try {
        return makeHeadFitRunner({o.fitter, o.dataDir, o.model}, dlib);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
}

}  // namespace mirror_eval::aam_report
