#pragma once
// A hand-like occluder in front of a rendered head (the fit must hold, or let go, when a hand
// covers part of the face): a palm, four fingers and a thumb in one skin colour with a little
// shading, drawn anti-aliased.

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace headgen {

struct Hand {
    bool present = false;
    Eigen::Vector2d palm = Eigen::Vector2d::Zero();  ///< palm centre, image pixels
    double width = 0;                                ///< palm width, pixels
    double angleDeg = 0;  ///< the fingers' direction from image up, clockwise on screen
};

/// Draws the hand into `frame` (CV_32FC3 BGR, 0..255) in colour `skin`; returns its coverage,
/// CV_32F 0..1 of the frame's size (all 0 when the hand is not present).
cv::Mat drawHand(cv::Mat& frame, const Hand& hand, const cv::Scalar& skin);

}  // namespace headgen
