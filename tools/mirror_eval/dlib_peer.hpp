#pragma once
// The peer `mirror-eval aam` measures the AAM fit against: dlib's HOG face detector (its boxes
// go to both) and its 68-point shape predictor (Kazemi and Sullivan's regression trees, trained
// on iBUG 300-W; it answers in iBUG order). From Debian's libdlib-dev and libdlib-data: tests and
// tools only, the predictor model's terms rule out shipping it.

#include "head_fit_runner.hpp"

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace mirror_eval {

inline constexpr const char* kDlibShapePredictor =
    "/usr/share/dlib/shape_predictor_68_face_landmarks.dat";

class DlibPeer {
public:
    /// Loads the predictor; throws std::runtime_error (one line) when it cannot be read.
    explicit DlibPeer(const std::string& predictorPath = kDlibShapePredictor, int upsample = 0);
    ~DlibPeer();
    DlibPeer(const DlibPeer&) = delete;
    DlibPeer& operator=(const DlibPeer&) = delete;

    /// Every face the HOG detector finds in `grey` (8-bit), upsampled `upsample` times first.
    std::vector<FaceBoxPx> detect(const cv::Mat& grey);
    /// The detection that overlaps `truthBox` most (IoU at least `minIou`), or none.
    std::optional<FaceBoxPx> detectNear(const cv::Mat& grey, const FaceBoxPx& truthBox,
                                        double minIou = 0.25);
    /// The 68 iBUG points of the face in `box`.
    std::vector<Eigen::Vector2d> landmarks(const cv::Mat& grey, const FaceBoxPx& box);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Intersection over union of two boxes.
double iou(const FaceBoxPx& a, const FaceBoxPx& b) noexcept;
/// The bounding box of points.
FaceBoxPx boundingBoxOf(const std::vector<Eigen::Vector2d>& points);

}  // namespace mirror_eval
