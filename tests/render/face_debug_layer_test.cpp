// FaceDebugLayer with the AAM (§5.3): each face's fitted mesh is drawn over the video, white when
// the fit holds, red when it failed (the face keeps the 2D pose), not at all when it was not
// fitted or the layer is hidden; and drawing it allocates nothing.
#include "render/face_debug_layer.hpp"

#include "alloc_counter.hpp"
#include "gl_test_context.hpp"
#include "render/renderer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <vector>

namespace {

using testing_support::GlTestContext;
using testing_support::Rgba;

constexpr int kWidth = 320, kHeight = 240;

struct Counts {
    int white = 0, red = 0;
};

Counts countMeshPixels(const GlTestContext& gl)
{
    Counts c;
    for (int y = 0; y < gl.height(); ++y)
        for (int x = 0; x < gl.width(); ++x) {
            const Rgba p = gl.pixel(x, y);
            if (p.r > 200 && p.g > 200 && p.b > 200)
                ++c.white;
            if (p.r > 180 && p.g < 110 && p.b < 110)
                ++c.red;
        }
    return c;
}

/// A fit whose mesh is a square of two triangles in the middle of the image.
vision::FaceFit squareFit(bool ok)
{
    vision::FaceFit fit;
    fit.faceId = 1;
    fit.fitted = true;
    fit.plausible = true;
    fit.outcome = ok ? vision::AamFitOutcome::Converged : vision::AamFitOutcome::Rejected;
    fit.vertexCount = 4;
    fit.vertices[0] = {110.f, 70.f};
    fit.vertices[1] = {210.f, 70.f};
    fit.vertices[2] = {210.f, 170.f};
    fit.vertices[3] = {110.f, 170.f};
    return fit;
}

class FaceDebugLayerTest : public ::testing::Test {
protected:
    GlTestContext gl{kWidth, kHeight};
    vision::ImageBuffer video{kWidth, kHeight, vision::PixelFormat::RGB24};

    void SetUp() override
    {
        for (int y = 0; y < kHeight; ++y)
            std::memset(video.view().row(y), 128, static_cast<std::size_t>(kWidth) * 3);
    }

    Counts draw(render::Renderer& renderer)
    {
        EXPECT_TRUE(renderer.draw(video.view(), kWidth, kHeight, nullptr)) << renderer.lastError();
        gl.read();
        return countMeshPixels(gl);
    }
};

TEST_F(FaceDebugLayerTest, TheFittedMeshIsWhiteWhenItHoldsRedWhenNotAndAbsentWhenNotFitted)
{
    render::Renderer renderer({kWidth, kHeight}, vision::PixelFormat::RGB24,
                              render::RendererOptions{false, {}, false});
    render::FaceDebugLayer layer;
    renderer.addLayer(&layer);
    const std::array<std::array<int, 3>, 2> triangles{{{0, 1, 2}, {0, 2, 3}}};
    layer.setMeshTriangles(triangles);
    layer.setVisible(true);

    const Counts none = draw(renderer);
    EXPECT_EQ(none.white, 0);
    EXPECT_EQ(none.red, 0);

    vision::FaceFit fit = squareFit(true);
    layer.updateFits({&fit, 1});
    const Counts held = draw(renderer);
    // Five edges of 100-141 px, a pixel wide.
    EXPECT_GT(held.white, 400);
    EXPECT_EQ(held.red, 0);

    fit = squareFit(false);
    layer.updateFits({&fit, 1});
    const Counts failed = draw(renderer);
    EXPECT_GT(failed.red, 400);
    EXPECT_EQ(failed.white, 0);

    fit.fitted = false;
    layer.updateFits({&fit, 1});
    const Counts notFitted = draw(renderer);
    EXPECT_EQ(notFitted.white + notFitted.red, 0);

    fit = squareFit(true);
    layer.updateFits({&fit, 1});
    layer.setVisible(false);
    const Counts hidden = draw(renderer);
    EXPECT_EQ(hidden.white + hidden.red, 0);
}

TEST_F(FaceDebugLayerTest, DrawingTheMeshAllocatesNothing)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    render::Renderer renderer({kWidth, kHeight}, vision::PixelFormat::RGB24,
                              render::RendererOptions{false, {}, false});
    render::FaceDebugLayer layer;
    renderer.addLayer(&layer);
    const std::array<std::array<int, 3>, 2> triangles{{{0, 1, 2}, {0, 2, 3}}};
    layer.setMeshTriangles(triangles);
    layer.setVisible(true);
    const std::array<vision::FaceFit, 2> fits{squareFit(true), squareFit(false)};
    layer.updateFits(fits);
    for (int i = 0; i < 4; ++i)  // warm-up: llvmpipe compiles shader variants on first use
        draw(renderer);
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        for (int i = 0; i < 5; ++i) {
            layer.updateFits(fits);
            renderer.draw(video.view(), kWidth, kHeight, nullptr);
        }
        counts = scope.counts();
    }
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}

}  // namespace
