#include "vision/pipeline.hpp"

#include "vision/frame_check_stage.hpp"

#include <gtest/gtest.h>

namespace {

using vision::ImageBuffer;
using vision::PixelFormat;

struct CountingStage final : vision::Stage {
    int calls = 0;
    const char* name() const noexcept override { return "count"; }
    void process(vision::FrameState&) noexcept override { ++calls; }
};

TEST(FrameCheckStage, PassesGoodFramesAndRejectsBadOnes)
{
    ImageBuffer good(32, 16, PixelFormat::RGB24), wrongSize(16, 16, PixelFormat::RGB24),
        wrongFormat(32, 16, PixelFormat::BGR24);
    vision::FrameCheckStage check({32, 16}, PixelFormat::RGB24);
    auto run = [&](vision::ConstImageView img) {
        vision::FrameState s;
        vision::Pipeline::begin(s, vision::Frame{img, 0, 0});
        check.process(s);
        return s;
    };
    EXPECT_TRUE(run(good.view()).valid);
    EXPECT_FALSE(run(wrongSize.view()).valid);
    EXPECT_FALSE(run(wrongFormat.view()).valid);
    EXPECT_FALSE(run(vision::ConstImageView{}).valid);
    vision::ConstImageView shortStride = good.view();
    shortStride.stride = 10;
    EXPECT_STRNE(run(shortStride).problem, "");
}

TEST(Pipeline, StopsAtTheFirstInvalidatingStage)
{
    vision::Pipeline p;
    p.add(std::make_unique<vision::FrameCheckStage>(vision::Size{8, 8}, PixelFormat::RGB24));
    auto counter = std::make_unique<CountingStage>();
    CountingStage* c = counter.get();
    p.add(std::move(counter));
    ImageBuffer good(8, 8, PixelFormat::RGB24), bad(4, 4, PixelFormat::RGB24);
    vision::FrameState s;
    vision::Pipeline::begin(s, {good.view(), 1, 0});
    p.run(s);
    EXPECT_EQ(c->calls, 1);
    vision::Pipeline::begin(s, {bad.view(), 2, 0});
    p.run(s);
    EXPECT_EQ(c->calls, 1);
    EXPECT_FALSE(s.valid);
}

TEST(Pipeline, RefusesMoreThanItsFixedCapacity)
{
    vision::Pipeline p;
    for (std::size_t i = 0; i < vision::Pipeline::kMaxStages; ++i)
        p.add(std::make_unique<CountingStage>());
    EXPECT_THROW(p.add(std::make_unique<CountingStage>()), std::length_error);
}

TEST(ImageBuffer, RejectsAbsurdSizesAndOddYuv)
{
    EXPECT_THROW(ImageBuffer(0, 10, PixelFormat::RGB24), std::invalid_argument);
    EXPECT_THROW(ImageBuffer(100000, 10, PixelFormat::RGB24), std::invalid_argument);
    EXPECT_THROW(ImageBuffer(11, 10, PixelFormat::NV12), std::invalid_argument);
    ImageBuffer nv(16, 8, PixelFormat::NV12);
    EXPECT_EQ(nv.bytes(), 16u * 8u * 3u / 2u);
}

}  // namespace
