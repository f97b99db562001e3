#pragma once
// The fitter `mirror-eval aam` scores, behind one small interface so the real-time AAM fit of
// vision/ (§5) plugs in beside the stand-in used until it exists. A runner gets one frame and the
// face box both peers are given (dlib's HOG detector's), and answers with every vertex of the
// tracked CANDIDE mesh in the image and, when it has them, the head's rotation and the six
// animation values. Frames of one sequence come in order; restart() says a new one begins.
//
// Conventions (headgen's truth, tools/headgen/head_projection.hpp): yaw turns the face to its
// left (the nose moves to the image's right), pitch turns it down, roll is clockwise on screen;
// the animation values in vision::kTrackedAnimationUnits order.

#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace mirror_eval {

/// A face box in image pixels (dlib's HOG rectangle, as both peers get it).
struct FaceBoxPx {
    double left = 0, top = 0, right = 0, bottom = 0;
    double width() const noexcept { return right - left; }
    double height() const noexcept { return bottom - top; }
    Eigen::Vector2d centre() const noexcept { return {0.5 * (left + right), 0.5 * (top + bottom)}; }
};

struct HeadAngles {
    double yawDeg = 0, pitchDeg = 0, rollDeg = 0;
};

struct HeadFit {
    /// False when the fit let the face go (diverged, failed verification): the frame is lost.
    bool held = false;
    /// Every vertex of mesh() in the image, pixels, in mesh order.
    std::vector<Eigen::Vector2d> vertices;
    std::optional<HeadAngles> angles;               ///< none: the runner has no 3D pose
    std::optional<std::array<float, 6>> animation;  ///< none: the runner has no expression
    int iterations = 0;                             ///< Gauss-Newton iterations this frame
};

class HeadFitRunner {
public:
    virtual ~HeadFitRunner() = default;
    /// What the rows it produces are called; a placeholder's says so.
    virtual std::string label() const = 0;
    /// True for a stand-in that does not fit (its pose and expression are unavailable).
    virtual bool placeholder() const = 0;
    /// The tracked CANDIDE mesh whose vertices fit() returns (vision::AamModel::mesh).
    virtual const vision::CandideMesh& mesh() const = 0;
    /// A new sequence, or an unrelated image: forget the previous frame's fit.
    virtual void restart() = 0;
    /// Fits the face `box` encloses in `grey` (8-bit, the whole frame).
    virtual HeadFit fit(const cv::Mat& grey, const FaceBoxPx& box) = 0;
};

struct HeadFitRunnerOptions {
    std::string fitter = "baseline";         ///< "aam" (vision's fit, needs model) or "baseline"
    std::string dataDir = "../shared/data";  ///< CANDIDE-3 and the baseline's calibration photos
    std::string model;                       ///< the .aam model file a real fit loads
};

class DlibPeer;

/// The runner `options.fitter` names. Throws std::invalid_argument (one line) for an unknown
/// name, std::runtime_error when its data cannot be read. `boxes` is the detector whose boxes
/// the runner will be given (the baseline calibrates its placement on them).
std::unique_ptr<HeadFitRunner> makeHeadFitRunner(const HeadFitRunnerOptions& options,
                                                 DlibPeer& boxes);

}  // namespace mirror_eval
