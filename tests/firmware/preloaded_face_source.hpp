#pragma once
// A camera-like source of real frames with a real face (the FGNet talking face), decoded before
// the test so the loop under test sees a source that allocates nothing per frame.
#include "platform/frame_source.hpp"
#include "platform/image_file.hpp"
#include "test_paths.hpp"

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace {

/// Real frames with a real face (the FGNet talking face), decoded before the test so that the
/// counted loop sees a camera-like source that allocates nothing: the frames play forwards then
/// backwards, so the face keeps moving smoothly.
class PreloadedFaceSource final : public platform::FrameSource {
public:
    explicit PreloadedFaceSource(int count)
    {
        for (int i = 0; i < count; ++i) {
            char name[64];
            std::snprintf(name, sizeof name, "fgnet_talking_face/images/franck_%05d.jpg", i);
            frames_.push_back(platform::loadImageFile(testing_support::sharedData(name)));
        }
    }
    /// Other frames (a facegen sequence's), `frameNs` apart.
    PreloadedFaceSource(const std::vector<std::string>& paths, std::int64_t frameNs)
        : frameNs_(frameNs)
    {
        for (const std::string& path : paths)
            frames_.push_back(platform::loadImageFile(path));
    }
    const char* description() const noexcept override { return "preloaded frames"; }
    vision::Size size() const noexcept override
    {
        return {frames_[0].view().width, frames_[0].view().height};
    }
    vision::PixelFormat format() const noexcept override { return frames_[0].view().format; }
    platform::SourceStatus next(vision::Frame& frame) noexcept override
    {
        const int n = static_cast<int>(frames_.size());
        const int period = 2 * n - 2;
        const int k = static_cast<int>(sequence_ % static_cast<std::uint64_t>(period));
        const int index = k < n ? k : period - k;
        frame.image = frames_[static_cast<std::size_t>(index)].view();
        frame.sequence = sequence_++;
        frame.timestampNs = static_cast<std::int64_t>(frame.sequence) * frameNs_;
        return platform::SourceStatus::Ok;
    }

private:
    std::vector<vision::ImageBuffer> frames_;
    std::uint64_t sequence_ = 0;
    std::int64_t frameNs_ = 40000000;  ///< FGNet's 25 fps
};

}  // namespace
