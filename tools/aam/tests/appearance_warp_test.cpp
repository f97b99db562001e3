// The piecewise affine warp (§5, 5.3.1): a face of a known affine of the mean shape warps a linear
// ramp to that ramp's values at the mapped pixels (bilinear sampling is exact on a ramp); the
// resampling between resolutions of one frame keeps a smooth image.
#include "appearance_warp.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

vision::CandideMesh twoTriangles()
{
    vision::CandideMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.candideNumber = {0, 1, 2, 3};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

const aam::Shape2d kSquare{{0, 0}, {1, 0}, {1, 1}, {0, 1}};

TEST(AppearanceWarp, AnAffineFaceWarpsARampExactly)
{
    cv::Mat ramp(200, 200, CV_8U);
    for (int y = 0; y < 200; ++y) {
        for (int x = 0; x < 200; ++x)
            ramp.at<unsigned char>(y, x) = static_cast<unsigned char>((x + 2 * y) / 3);
    }
    const aam::AppearanceFrame frame = aam::appearanceFrame(twoTriangles(), kSquare, 33);
    // The face in the image: the square turned 0.3 rad, 120 px across, at (40, 30).
    const double c = 120 * std::cos(0.3), s = 120 * std::sin(0.3);
    aam::Shape2d face;
    for (const auto& p : kSquare)
        face.emplace_back(40 + c * p.x() - s * p.y(), 30 + s * p.x() + c * p.y());
    const Eigen::VectorXd warped = aam::warpToFrame(ramp, face, twoTriangles(), frame);
    ASSERT_EQ(warped.size(), static_cast<Eigen::Index>(frame.pixels.size()));
    double worst = 0;
    for (std::size_t i = 0; i < frame.pixels.size(); ++i) {
        const Eigen::Vector2d unit =
            (Eigen::Vector2d(frame.pixels[i].x, frame.pixels[i].y) - Eigen::Vector2d(1, 1)) /
            frame.scale;
        const double x = 40 + c * unit.x() - s * unit.y(), y = 30 + s * unit.x() + c * unit.y();
        worst = std::max(worst, std::abs(warped(static_cast<Eigen::Index>(i)) - (x + 2 * y) / 3));
    }
    EXPECT_LT(worst, 1.0);  // the ramp's own rounding to 8 bits
}

TEST(AppearanceWarp, ResamplingBetweenResolutionsKeepsASmoothImage)
{
    const aam::AppearanceFrame coarse = aam::appearanceFrame(twoTriangles(), kSquare, 32);
    const aam::AppearanceFrame fine = aam::appearanceFrame(twoTriangles(), kSquare, 128);
    Eigen::VectorXd values(static_cast<Eigen::Index>(coarse.pixels.size()));
    for (std::size_t i = 0; i < coarse.pixels.size(); ++i)
        values(static_cast<Eigen::Index>(i)) = coarse.pixels[i].x + coarse.pixels[i].y;
    const Eigen::VectorXd up = aam::resampledTo(coarse, values, fine);
    int finite = 0;
    for (std::size_t i = 0; i < fine.pixels.size(); ++i) {
        if (!std::isfinite(up(static_cast<Eigen::Index>(i))))
            continue;
        ++finite;
        const Eigen::Vector2d unit =
            (Eigen::Vector2d(fine.pixels[i].x, fine.pixels[i].y) - Eigen::Vector2d(1, 1)) /
            fine.scale;
        const Eigen::Vector2d inCoarse = unit * coarse.scale + Eigen::Vector2d(1, 1);
        EXPECT_NEAR(up(static_cast<Eigen::Index>(i)), inCoarse.x() + inCoarse.y(), 1e-6);
    }
    EXPECT_GT(finite, static_cast<int>(fine.pixels.size() * 95 / 100));
}

}  // namespace
