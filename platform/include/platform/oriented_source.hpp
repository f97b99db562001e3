#pragma once
// OrientedSource: a camera mounted upside down or seen through a mirror, set upright before
// anything looks at its frames (rpicam-apps' --rotation 0|180, --hflip, --vflip).

#include "platform/frame_source.hpp"
#include "vision/image.hpp"

#include <memory>
#include <string>

namespace platform {

/// How to turn the camera's frames: rotation 180 is both flips; the flips compose with it.
struct Orientation {
    int rotation = 0;  ///< 0 or 180
    bool hflip = false;
    bool vflip = false;

    /// The net flips: what is done to each frame.
    bool flipsX() const noexcept { return hflip != (rotation == 180); }
    bool flipsY() const noexcept { return vflip != (rotation == 180); }
    bool identity() const noexcept { return !flipsX() && !flipsY(); }
};

/// \class OrientedSource
/// Wraps a source and delivers each of its frames flipped as `orientation` says, into a buffer
/// made in the constructor (next() copies, never allocates). Packed formats only (RGB24, BGR24,
/// XRGB8888, Gray8): the constructor throws std::runtime_error with one line for another.
/// Everything else (status, errors, rebuild and restart questions) is the inner source's.
class OrientedSource final : public FrameSource {
public:
    OrientedSource(std::unique_ptr<FrameSource> inner, Orientation orientation);

    const char* description() const noexcept override { return description_.c_str(); }
    vision::Size size() const noexcept override { return inner_->size(); }
    vision::PixelFormat format() const noexcept override { return inner_->format(); }
    SourceStatus next(vision::Frame& frame) noexcept override;
    std::int64_t lastWaitNs() const noexcept override { return inner_->lastWaitNs(); }
    const char* lastError() const noexcept override { return inner_->lastError(); }
    bool needsPipelineRebuild() const noexcept override { return inner_->needsPipelineRebuild(); }
    bool needsProcessRestart() const noexcept override { return inner_->needsProcessRestart(); }

private:
    std::unique_ptr<FrameSource> inner_;
    Orientation orientation_;
    vision::ImageBuffer buffer_;
    std::string description_;
};

}  // namespace platform
