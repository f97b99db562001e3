#pragma once
// The scene model of cardgen: a camera looking at a background photograph, a solid-coloured card
// (A5 construction paper) in 3D in front of it, optionally a skin-coloured hand, a distractor patch
// of a similar colour, lighting/gain, sensor noise and interlacing. One FrameSpec describes
// everything in one frame; renderFrame() turns it into pixels and the spec's card quad is the
// ground truth.

#include "platform/card_raster.hpp"
#include "vision/geometry.hpp"

#include <opencv2/core.hpp>
#include <string>

namespace cardgen {

/// The card in 3D: centre in pixels, size, and its rotation (radians) about the camera's axes.
struct CardPose {
    double cx = 0.0;  ///< projected centre, pixels
    double cy = 0.0;
    double halfHeight = 80;  ///< half the short side in pixels when facing the camera
    double yaw = 0.0;        ///< about the vertical axis
    double pitch = 0.0;      ///< about the horizontal axis
    double roll = 0.0;       ///< in the image plane, clockwise on screen
};

/// A5 landscape: long side / short side.
inline constexpr double kCardAspect = 210.0 / 148.0;

/// Corners of the card seen through a pinhole camera of focal length `focal` pixels, clockwise on
/// screen from the card's top-left corner.
vision::Quad projectCard(const CardPose& pose, double focal) noexcept;

/// Shading of the card surface: brighter or darker with the tilt, a gradient turning with time.
platform::CardPaint shadeCard(const CardPose& pose, cv::Vec3b rgb, double timeSec,
                              std::uint32_t noiseSeed) noexcept;

/// A hand-like skin-coloured blob: palm and fingers pointing along `angle` (radians, 0 = +x).
struct HandPose {
    double x = 0.0;  ///< palm centre, pixels
    double y = 0.0;
    double angle = 0.0;
    double radius = 30.0;  ///< palm radius, pixels
    /// An arm behind the palm (opposite the fingers), this long in palm radii; 0: a hand alone.
    double armLength = 0.0;
    double skin[3] = {138.0, 170.0, 222.0};  ///< BGR
};

/// Everything visible in one frame.
struct FrameSpec {
    bool card = true;  ///< draw the card (false: no card in the scene at all)
    vision::Quad quad{};
    platform::CardPaint paint;
    bool distractor = false;  ///< a smaller patch of a similar colour, elsewhere
    vision::Quad distractorQuad{};
    platform::CardPaint distractorPaint;
    bool hand = false;
    HandPose handPose;
    /// A skin-coloured hand behind the card (someone else's, a distractor): drawn under the card.
    bool backHand = false;
    HandPose backHandPose;
    /// Interlacing: the odd rows show the scene of the previous field (the card, the distractor
    /// and the hand where they were half a frame earlier).
    bool interlace = false;
    vision::Quad previousQuad{};
    vision::Quad previousDistractorQuad{};
    HandPose previousHandPose;
    double gain = 1.0;        ///< whole-scene light or camera gain; saturates at 255
    double noiseSigma = 1.5;  ///< sensor noise, grey levels (Gaussian, per channel)
    double blurSigma = 0.0;   ///< lens blur before the sensor (Gaussian, pixels; 0: none)
};

/// Reads a photograph and scales and crops it to cover `size` (BGR). Throws std::runtime_error
/// "background PATH: cannot read" when OpenCV cannot decode it.
cv::Mat loadBackground(const std::string& path, cv::Size size);

/// Renders the frame (BGR, the background's size). `noiseSeed` makes the sensor noise repeatable.
cv::Mat renderFrame(const cv::Mat& background, const FrameSpec& spec, std::uint64_t noiseSeed);

/// Draws the hand into a BGR image (anti-aliased).
void drawHand(cv::Mat& bgr, const HandPose& hand);

/// The training frame's card: held close to the camera, filling the view, its edges just outside
/// the image.
vision::Quad trainingQuad(cv::Size size) noexcept;

/// True when any part of the quad lies within the image (pixel centres 0..width-1).
bool quadTouchesImage(const vision::Quad& quad, cv::Size size) noexcept;

/// The card's corners as the truth gives them: clockwise on screen from the top-left one (the
/// corner with the smallest x + y). The drawn quad starts at the card's own top-left corner,
/// which is another one when the card is turned by about 45 degrees or more.
vision::Quad truthCorners(const vision::Quad& quad) noexcept;

}  // namespace cardgen
