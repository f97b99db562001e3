// The appearance frame (§5, 5.3.1): the mean shape scaled into the frame's width, every pixel
// inside the mesh listed once with its triangle, its barycentric coordinates giving the pixel
// back; a bad width refused with one line.
#include "appearance_frame.hpp"

#include <gtest/gtest.h>

namespace {

/// A unit square of two triangles, and an extra vertex inside no triangle.
vision::CandideMesh twoTriangles()
{
    vision::CandideMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.candideNumber = {0, 1, 2, 3};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

const aam::Shape2d kSquare{{10, 20}, {30, 20}, {30, 40}, {10, 40}};

TEST(AppearanceFrame, ScalesTheMeanIntoTheWidth)
{
    const aam::AppearanceFrame f = aam::appearanceFrame(twoTriangles(), kSquare, 23);
    EXPECT_EQ(f.width, 23);
    EXPECT_EQ(f.height, 23);
    EXPECT_DOUBLE_EQ(f.scale, 1.0);
    EXPECT_EQ(f.meanShape[0], Eigen::Vector2d(1, 1));
    EXPECT_EQ(f.meanShape[2], Eigen::Vector2d(21, 21));
}

TEST(AppearanceFrame, ListsEveryInsidePixelOnceWithItsTriangle)
{
    const vision::CandideMesh mesh = twoTriangles();
    const aam::AppearanceFrame f = aam::appearanceFrame(mesh, kSquare, 23);
    EXPECT_EQ(f.pixels.size(), 21u * 21u);  // x, y = 1 .. 21, the diagonal in the first triangle
    for (const aam::FramePixel& p : f.pixels) {
        const auto& tri = mesh.triangles[static_cast<std::size_t>(p.triangle)];
        const Eigen::Vector2d back =
            p.barycentric(0) * f.meanShape[static_cast<std::size_t>(tri[0])] +
            p.barycentric(1) * f.meanShape[static_cast<std::size_t>(tri[1])] +
            p.barycentric(2) * f.meanShape[static_cast<std::size_t>(tri[2])];
        EXPECT_NEAR((back - Eigen::Vector2d(p.x, p.y)).norm(), 0, 1e-9);
        EXPECT_GE(p.barycentric.minCoeff(), -1e-9);
        EXPECT_EQ(p.triangle, p.x >= p.y ? 0 : 1);  // the shared diagonal goes to the first
    }
}

TEST(AppearanceFrame, RefusesABadWidth)
{
    try {
        aam::appearanceFrame(twoTriangles(), kSquare, 8);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "appearance frame: width 8 is not in [16, 1024]");
    }
}

}  // namespace
