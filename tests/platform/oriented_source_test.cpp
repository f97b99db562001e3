// Camera orientation as rpicam-apps has it: --rotation 180 is both flips, --hflip and --vflip
// compose with it; everything else is the inner source's.
#include "platform/oriented_source.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <stdexcept>

namespace {

/// 3x2 RGB24 frames whose pixel (x, y) has R = x, G = y; Lost when asked.
class TinySource final : public platform::FrameSource {
public:
    explicit TinySource(vision::PixelFormat format = vision::PixelFormat::RGB24, int width = 3)
        : image_(width, 2, format)
    {
    }
    const char* description() const noexcept override { return "tiny"; }
    vision::Size size() const noexcept override { return image_.view().size(); }
    vision::PixelFormat format() const noexcept override { return image_.view().format; }
    platform::SourceStatus next(vision::Frame& frame) noexcept override
    {
        if (lost)
            return platform::SourceStatus::Lost;
        const vision::ImageView v = image_.view();
        const int bpp = vision::bytesPerPixel(v.format);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) {
                v.row(y)[x * bpp] = static_cast<std::uint8_t>(x);
                if (bpp > 1)
                    v.row(y)[x * bpp + 1] = static_cast<std::uint8_t>(y);
            }
        frame.image = image_.view();
        return platform::SourceStatus::Ok;
    }
    const char* lastError() const noexcept override { return "tiny lost"; }
    bool lost = false;

private:
    vision::ImageBuffer image_;
};

/// (R, G) = the inner (x, y) shown at (x, y) of the oriented frame.
std::pair<int, int> at(const vision::Frame& f, int x, int y)
{
    return {f.image.row(y)[x * 3], f.image.row(y)[x * 3 + 1]};
}

}  // namespace

TEST(OrientedSource, Rotation180IsBothFlipsAndFlipsCompose)
{
    struct Case {
        platform::Orientation o;
        int srcX, srcY;  // what lands at (0, 0)
    };
    for (const Case c : {Case{{180, false, false}, 2, 1}, Case{{0, true, false}, 2, 0},
                         Case{{0, false, true}, 0, 1}, Case{{180, true, false}, 0, 1},
                         Case{{0, true, true}, 2, 1}}) {
        platform::OrientedSource source(std::make_unique<TinySource>(), c.o);
        vision::Frame frame;
        ASSERT_EQ(source.next(frame), platform::SourceStatus::Ok);
        EXPECT_EQ(at(frame, 0, 0), std::pair(c.srcX, c.srcY))
            << c.o.rotation << " " << c.o.hflip << " " << c.o.vflip;
        EXPECT_EQ(at(frame, 2, 1), std::pair(2 - c.srcX, 1 - c.srcY));
    }
    EXPECT_TRUE((platform::Orientation{180, true, true}.identity()));
}

TEST(OrientedSource, PassesLossThroughAndRefusesPlanarFormats)
{
    auto inner = std::make_unique<TinySource>();
    TinySource* tiny = inner.get();
    platform::OrientedSource source(std::move(inner), {180, false, false});
    tiny->lost = true;
    vision::Frame frame;
    EXPECT_EQ(source.next(frame), platform::SourceStatus::Lost);
    EXPECT_STREQ(source.lastError(), "tiny lost");
    EXPECT_NE(std::string(source.description()).find("rotation 180"), std::string::npos);
    EXPECT_THROW(platform::OrientedSource(
                     std::make_unique<TinySource>(vision::PixelFormat::YUYV, 4), {0, true, false}),
                 std::runtime_error);
}
