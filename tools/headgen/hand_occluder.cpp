// The hand occluder: shapes drawn 4x larger and shrunk, so its outline is anti-aliased.
#include "hand_occluder.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace headgen {

namespace {

constexpr int kSuper = 4;

cv::Point at(const Eigen::Vector2d& p)
{
    return {static_cast<int>(p.x() * kSuper), static_cast<int>(p.y() * kSuper)};
}

/// The palm ellipse, four fingers and a thumb, in frame pixels times kSuper: coverage (1) and
/// shading (the finger gaps darker).
void drawShapes(cv::Mat& cover, cv::Mat& shade, const Hand& h)
{
    constexpr double kRad = 3.14159265358979323846 / 180.0;
    const Eigen::Vector2d up(std::sin(h.angleDeg * kRad), -std::cos(h.angleDeg * kRad));
    const Eigen::Vector2d side(-up.y(), up.x());
    const double w = h.width;
    const int palmW = static_cast<int>(0.5 * w * kSuper),
              palmH = static_cast<int>(0.6 * w * kSuper);
    cv::ellipse(cover, at(h.palm), cv::Size(palmW, palmH), h.angleDeg, 0, 360, 1.0, cv::FILLED);
    cv::ellipse(shade, at(h.palm), cv::Size(palmW, palmH), h.angleDeg, 0, 360, 0.95, cv::FILLED);
    const double lengths[4] = {0.75, 0.9, 0.85, 0.65};
    for (int f = 0; f < 4; ++f) {
        const double offset = (-0.36 + 0.24 * f) * w;
        const Eigen::Vector2d base = h.palm + 0.35 * w * up + offset * side;
        const Eigen::Vector2d tip = base + lengths[f] * w * up + 0.04 * (f - 1.5) * w * side;
        const int thick = static_cast<int>(0.21 * w * kSuper);
        cv::line(cover, at(base), at(tip), 1.0, thick, cv::LINE_8);
        cv::line(shade, at(base), at(tip), 0.82, thick, cv::LINE_8);
        cv::line(shade, at(base), at(tip), 1.0, std::max(1, thick * 2 / 3), cv::LINE_8);
    }
    const Eigen::Vector2d thumbBase = h.palm - 0.4 * w * side + 0.05 * w * up;
    const Eigen::Vector2d thumbTip = thumbBase - 0.45 * w * side + 0.45 * w * up;
    cv::line(cover, at(thumbBase), at(thumbTip), 1.0, static_cast<int>(0.25 * w * kSuper));
    cv::line(shade, at(thumbBase), at(thumbTip), 0.9, static_cast<int>(0.25 * w * kSuper));
}

}  // namespace

cv::Mat drawHand(cv::Mat& frame, const Hand& hand, const cv::Scalar& skin)
{
    cv::Mat coverage(frame.size(), CV_32F, cv::Scalar(0));
    if (!hand.present || hand.width <= 0)
        return coverage;
    cv::Mat cover(frame.rows * kSuper, frame.cols * kSuper, CV_32F, cv::Scalar(0));
    cv::Mat shade(cover.size(), CV_32F, cv::Scalar(1));
    drawShapes(cover, shade, hand);
    cv::resize(cover, coverage, frame.size(), 0, 0, cv::INTER_AREA);
    cv::Mat shading;
    cv::resize(shade, shading, frame.size(), 0, 0, cv::INTER_AREA);
    for (int y = 0; y < frame.rows; ++y) {
        auto* px = frame.ptr<cv::Vec3f>(y);
        for (int x = 0; x < frame.cols; ++x) {
            const float a = coverage.at<float>(y, x);
            if (a <= 0.f)
                continue;
            const float s = shading.at<float>(y, x);
            for (int c = 0; c < 3; ++c)
                px[x][c] = (1 - a) * px[x][c] + a * s * static_cast<float>(skin[c]);
        }
    }
    return coverage;
}

}  // namespace headgen
