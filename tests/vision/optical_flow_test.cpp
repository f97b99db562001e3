// Pyramidal Lucas-Kanade on synthetic images with known motion: sub-pixel shifts within 0.1 px,
// larger motion through the pyramid, a rotation and scale recovered by the motion model from the
// tracked points, forward-backward flags for occluded points, border behaviour, no allocation.
#include "vision/optical_flow.hpp"

#include "alloc_counter.hpp"
#include "vision/corner_detector.hpp"
#include "vision/motion_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using vision::FlowStatus;
using vision::ImageBuffer;
using vision::ImagePyramid;
using vision::Point2f;
using vision::PyramidalLucasKanade;

namespace {

constexpr int kW = 320;
constexpr int kH = 240;
constexpr float kPi = 3.14159265f;

// A smooth, non-repeating texture defined everywhere, so a shifted or rotated copy is exact at
// sub-pixel positions: value noise (hashed lattice values, smoothstep-interpolated) in three
// octaves. Sinusoids would repeat and let the tracker lock on a wrong period.
float lattice(int x, int y)
{
    std::uint32_t h = std::uint32_t(x) * 374761393u + std::uint32_t(y) * 668265263u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return float((h ^ (h >> 16)) & 0xffff) / 65535.f - 0.5f;
}

float valueNoise(float x, float y)
{
    const float fx = std::floor(x), fy = std::floor(y);
    const int ix = int(fx), iy = int(fy);
    float u = x - fx, v = y - fy;
    u = u * u * (3.f - 2.f * u);
    v = v * v * (3.f - 2.f * v);
    const float a = lattice(ix, iy) + u * (lattice(ix + 1, iy) - lattice(ix, iy));
    const float b = lattice(ix, iy + 1) + u * (lattice(ix + 1, iy + 1) - lattice(ix, iy + 1));
    return a + v * (b - a);
}

float texture(float x, float y)
{
    return 128.f + 150.f * valueNoise(x / 16.f, y / 16.f) +
           90.f * valueNoise(x / 8.f + 100.f, y / 8.f) + 50.f * valueNoise(x / 4.f, y / 4.f + 50.f);
}

float occluder(float x, float y)
{
    return 128.f + 60.f * std::sin(0.7f * x) * std::cos(0.9f * y + 0.5f);
}

// Renders the texture seen through the inverse of p' = R(th) s (p - c) + c + t.
ImageBuffer render(float s, float th, float tx, float ty, bool occlude = false)
{
    ImageBuffer img(kW, kH, vision::PixelFormat::Gray8);
    const float cx = kW / 2.f, cy = kH / 2.f;
    const float ct = std::cos(th), st = std::sin(th);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float u = (float(x) - cx - tx) / s;
            const float v = (float(y) - cy - ty) / s;
            float val = texture(ct * u + st * v + cx, -st * u + ct * v + cy);
            if (occlude && x >= 200 && x < 260 && y >= 60 && y < 120)
                val = occluder(float(x), float(y));
            img.view().row(y)[x] =
                static_cast<std::uint8_t>(std::lround(std::clamp(val, 0.f, 255.f)));
        }
    return img;
}

std::vector<Point2f> grid(int x0, int x1, int y0, int y1, int step)
{
    std::vector<Point2f> pts;
    for (int y = y0; y < y1; y += step)
        for (int x = x0; x < x1; x += step)
            pts.push_back({float(x), float(y)});
    return pts;
}

}  // namespace

TEST(OpticalFlow, SubPixelShiftsWithinATenthOfAPixel)
{
    const ImageBuffer a = render(1.f, 0.f, 0.f, 0.f);
    ImagePyramid pa({kW, kH}, 4), pb({kW, kH}, 4);
    ASSERT_TRUE(pa.build(a.view()));
    PyramidalLucasKanade lk;
    const std::vector<Point2f> pts = grid(30, 290, 30, 210, 20);
    const int n = int(pts.size());
    std::vector<Point2f> out(n);
    std::vector<FlowStatus> st(n);
    for (Point2f shift : {Point2f{0.3f, -0.45f}, Point2f{1.7f, 0.25f}, Point2f{-4.6f, 3.35f},
                          Point2f{9.2f, -6.8f}}) {
        const ImageBuffer b = render(1.f, 0.f, shift.x, shift.y);
        ASSERT_TRUE(pb.build(b.view()));
        const int tracked = lk.track(pa, pb, pts.data(), out.data(), st.data(), n);
        EXPECT_EQ(tracked, n) << shift.x << "," << shift.y;
        double worst = 0.0;
        for (int i = 0; i < n; ++i) {
            if (st[i] != FlowStatus::Tracked)
                continue;
            worst = std::max<double>(
                worst, std::hypot(out[i].x - pts[i].x - shift.x, out[i].y - pts[i].y - shift.y));
        }
        EXPECT_LT(worst, 0.1) << "shift " << shift.x << "," << shift.y;
    }
}

TEST(OpticalFlow, RotationAndScaleRecoveredByTheMotionModel)
{
    const ImageBuffer a = render(1.f, 0.f, 0.f, 0.f);
    const float th = 6.f * kPi / 180.f;
    const ImageBuffer b = render(1.05f, th, 2.5f, -1.5f);
    ImagePyramid pa({kW, kH}, 4), pb({kW, kH}, 4);
    ASSERT_TRUE(pa.build(a.view()));
    ASSERT_TRUE(pb.build(b.view()));
    // Corners of the face-sized box in the middle, tracked, and the similarity fitted about the
    // image centre (the centre of the synthetic motion).
    vision::CornerDetector corners({kW, kH}, {.maxCorners = 40, .minDistance = 8.f});
    vision::Corner found[40];
    const int n = corners.detect(a.view(), {100, 60, 120, 120}, found, 40);
    ASSERT_GE(n, 20);
    Point2f from[40], to[40];
    FlowStatus st[40];
    for (int i = 0; i < n; ++i)
        from[i] = found[i].position;
    PyramidalLucasKanade lk;
    const int tracked = lk.track(pa, pb, from, to, st, n);
    EXPECT_GE(tracked, n - 2);
    Point2f f2[40], t2[40];
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (st[i] == FlowStatus::Tracked) {
            f2[m] = from[i];
            t2[m++] = to[i];
        }
    vision::MotionModel model;
    vision::MotionFitOptions opt;
    opt.kind = vision::MotionKind::Similarity;
    opt.inlierDistance = 0.5f;
    EXPECT_GE(vision::fitMotionRobust(f2, t2, m, {kW / 2.f, kH / 2.f}, opt, model), m * 9 / 10);
    EXPECT_NEAR(model.scale(), 1.05f, 0.005f);
    EXPECT_NEAR(model.roll() * 180.f / kPi, 6.f, 0.2f);
    EXPECT_NEAR(model.b1, 2.5f, 0.15f);
    EXPECT_NEAR(model.b2, -1.5f, 0.15f);
}

TEST(OpticalFlow, ForwardBackwardFlagsOccludedPoints)
{
    const ImageBuffer a = render(1.f, 0.f, 0.f, 0.f);
    const ImageBuffer b = render(1.f, 0.f, 2.f, 1.f, true);  // a patch of other texture appears
    ImagePyramid pa({kW, kH}, 4), pb({kW, kH}, 4);
    ASSERT_TRUE(pa.build(a.view()));
    ASSERT_TRUE(pb.build(b.view()));
    vision::OpticalFlowOptions opt;
    opt.fbThreshold = 0.5f;
    PyramidalLucasKanade lk(opt);
    const std::vector<Point2f> pts = grid(30, 290, 30, 210, 10);
    const int n = int(pts.size());
    std::vector<Point2f> out(n);
    std::vector<FlowStatus> st(n);
    std::vector<float> fb(n);
    lk.track(pa, pb, pts.data(), out.data(), st.data(), n, fb.data());
    int inside = 0, insideRejected = 0, far = 0, farTracked = 0;
    for (int i = 0; i < n; ++i) {
        const Point2f p = pts[i];
        // Windows wholly inside the occluder, and windows well clear of it.
        if (p.x >= 210 && p.x < 250 && p.y >= 70 && p.y < 110) {
            ++inside;
            insideRejected += st[i] != FlowStatus::Tracked;
        } else if (p.x < 170 || p.y > 160) {
            ++far;
            farTracked += st[i] == FlowStatus::Tracked;
            EXPECT_LT(fb[i], 0.1f);
        }
    }
    ASSERT_GT(inside, 10);
    EXPECT_GE(insideRejected, inside * 9 / 10) << insideRejected << " of " << inside;
    EXPECT_EQ(farTracked, far);
}

TEST(OpticalFlow, FlatWindowsAndPointsLeavingTheImageAreLost)
{
    ImageBuffer flat(kW, kH, vision::PixelFormat::Gray8);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            flat.view().row(y)[x] = 90;
    ImagePyramid pa({kW, kH}, 3), pb({kW, kH}, 3);
    ASSERT_TRUE(pa.build(flat.view()));
    ASSERT_TRUE(pb.build(flat.view()));
    PyramidalLucasKanade lk;
    const Point2f p[1] = {{100.f, 100.f}};
    Point2f q[1];
    FlowStatus st[1];
    EXPECT_EQ(lk.track(pa, pb, p, q, st, 1), 0);
    EXPECT_EQ(st[0], FlowStatus::Lost);
    EXPECT_EQ(q[0], p[0]);

    // A point near the left edge, the texture moving it out of the frame.
    const ImageBuffer a = render(1.f, 0.f, 0.f, 0.f);
    const ImageBuffer b = render(1.f, 0.f, -6.f, 0.f);
    ASSERT_TRUE(pa.build(a.view()));
    ASSERT_TRUE(pb.build(b.view()));
    const Point2f edge[2] = {{3.f, 120.f}, {20.f, 120.f}};
    Point2f moved[2];
    FlowStatus es[2];
    lk.track(pa, pb, edge, moved, es, 2);
    EXPECT_EQ(es[0], FlowStatus::Lost);
    EXPECT_EQ(es[1], FlowStatus::Tracked);
    EXPECT_NEAR(moved[1].x, 14.f, 0.1f);

    // Garbage in (NaN, far outside) is Lost, not undefined.
    const Point2f bad[2] = {{std::nanf(""), 50.f}, {-1e9f, 1e9f}};
    Point2f badOut[2];
    FlowStatus bs[2];
    EXPECT_EQ(lk.track(pa, pb, bad, badOut, bs, 2), 0);
    EXPECT_EQ(bs[0], FlowStatus::Lost);
    EXPECT_EQ(bs[1], FlowStatus::Lost);
}

TEST(OpticalFlow, BadWindowIsRefused)
{
    vision::OpticalFlowOptions opt;
    opt.window = 14;
    EXPECT_THROW(PyramidalLucasKanade{opt}, std::runtime_error);
}

TEST(OpticalFlow, TrackingDoesNotAllocate)
{
    const ImageBuffer a = render(1.f, 0.f, 0.f, 0.f);
    const ImageBuffer b = render(1.02f, 0.03f, 1.3f, -0.7f);
    ImagePyramid pa({kW, kH}, 4), pb({kW, kH}, 4);
    PyramidalLucasKanade lk;
    vision::CornerDetector corners({kW, kH});
    vision::Corner found[50];
    Point2f from[50], to[50];
    FlowStatus st[50];
    float fb[50];
    vision::MotionModel model;
    testing_support::AllocationScope scope;
    ASSERT_TRUE(pa.build(a.view()));
    ASSERT_TRUE(pb.build(b.view()));
    const int n = corners.detect(a.view(), {80, 40, 160, 160}, found, 50);
    for (int i = 0; i < n; ++i)
        from[i] = found[i].position;
    EXPECT_GT(lk.track(pa, pb, from, to, st, n, fb), n / 2);
    EXPECT_GT(vision::fitMotionRobust(from, to, n, {160.f, 120.f}, {}, model), 0);
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}
