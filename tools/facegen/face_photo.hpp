#pragma once
// One IMM face photograph with its 58 hand-placed landmarks, the face frame derived from them
// (anchor, width, roll), the square box a Viola-Jones detector would give on it, and the soft head
// mask facegen cuts it out with.

#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace facegen {

/// IMM .asf point indices (image left/right, i.e. the person's right/left).
inline constexpr int kImmPoints = 58;

struct FacePhoto {
    std::string imagePath;
    std::string name;                              ///< e.g. "01-1m"
    std::array<cv::Point2d, kImmPoints> points{};  ///< pixels in the 640x480 photograph
};

/// Reads an IMM .asf file (relative coordinates, scaled by the host image's 640x480) and checks
/// its host image exists. Throws std::runtime_error with one line on any problem.
FacePhoto loadImmFace(const std::string& asfPath);

/// The face's own frame from its landmarks.
struct FaceFrame {
    cv::Point2d anchor;  ///< midway between the eye midpoint and the mouth centre
    double width = 0;    ///< jaw end to jaw end (IMM points 0 and 12), pixels
    double rollDeg = 0;  ///< midline (eye midpoint, nose, mouth centre) from vertical, clockwise
};
FaceFrame faceFrameOf(const FacePhoto& face);

/// Measured on the upright frontal IMM photographs (types 1, 2, 5, 6) with OpenCV's
/// haarcascade_frontalface_default (`facegen --measure-size`, see README.md): the detector's box
/// side over the landmark width, and its centre's offset from the anchor in the face frame, in
/// units of the width (x to the image right, y down, for an upright face). 160 photographs, all
/// detected; the ratio's standard deviation over them is 0.089. The jaw ends (IMM points 0, 12) lie
/// below the cheekbones, hence a box wider than that width.
inline constexpr double kBoxPerWidth = 1.394;
inline constexpr double kBoxOffsetX = -0.006;
inline constexpr double kBoxOffsetY = -0.134;

/// Rotates a vector clockwise on screen (y down) by `deg` degrees.
cv::Point2d rotateOnScreen(cv::Point2d v, double deg) noexcept;

/// The face's ground-truth box in its own photograph: centre and side (Viola-Jones convention).
struct FaceBox {
    cv::Point2d centre;
    double size = 0;
    double rollDeg = 0;
};
FaceBox faceBoxOf(const FaceFrame& frame) noexcept;

/// The head cut out of its photograph: a soft ellipse around face and hair, with the photograph's
/// plain backdrop keyed out, as alpha in 0..1 (CV_32F, the photograph's size).
cv::Mat headMask(const cv::Mat& photo, const FacePhoto& face);

/// The IMM photographs of upright frontal faces (types 1, 2, 5, 6: neutral, happy, spotlight,
/// free expression; 160 of 240), as paths of their .asf files under `immDir`, sorted.
std::vector<std::string> frontalImmFaces(const std::string& immDir);

/// Result of --measure-size: the detector's box against the landmark frame on many photographs.
struct SizeMeasurement {
    int photos = 0;
    int detected = 0;
    double boxPerWidth = 0, boxPerWidthStd = 0;
    double offsetX = 0, offsetY = 0;
};
/// Runs cv::CascadeClassifier (scale factor 1.1, min neighbours 3) on each photograph and, where
/// a detection contains the anchor, compares it with the landmark frame.
SizeMeasurement measureBoxAgainstLandmarks(const std::vector<std::string>& asfPaths,
                                           const std::string& cascadePath);

}  // namespace facegen
