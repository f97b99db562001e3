#pragma once
// SyntheticSource: a procedural camera scene, the default source when no camera is present.

#include "platform/frame_pacer.hpp"
#include "platform/frame_source.hpp"
#include "vision/image.hpp"

#include <cstdint>

namespace platform {

/// A deterministic procedural scene in RGB24 that never ends.
///
/// Each frame is a pure function of its index: a static textured background (gradients, a soft
/// window, a dark cupboard, a lamp glow, a floor and fine noise, so the image is nowhere flat), two
/// discs moving along Lissajous paths (something for motion detection), and a face-like figure
/// (skin-toned ellipse with hair, darker eyes, brows and mouth, on shoulders) swaying slowly. The
/// scene advances 1/30 s of scene time per frame index whatever the delivery rate, so a recorded
/// index always shows the same picture.
///
/// The background is rendered once in the constructor; next() copies it and draws the moving
/// shapes in their bounding boxes only, so a 640x480 frame costs well under a millisecond.
/// Coordinates follow the usual image convention: pixel (x, y) has its centre at (x, y).
class SyntheticSource final : public FrameSource {
public:
    /// `fps` > 0 paces delivery with a FramePacer; 0 delivers as fast as asked. Throws
    /// std::runtime_error for a size outside 16..16384 or a negative / non-finite fps.
    SyntheticSource(int width, int height, double fps, PacerClock& clock = monotonicPacerClock());

    const char* description() const noexcept override { return description_; }
    vision::Size size() const noexcept override { return {width_, height_}; }
    vision::PixelFormat format() const noexcept override { return vision::PixelFormat::RGB24; }
    SourceStatus next(vision::Frame& frame) noexcept override;
    std::int64_t lastWaitNs() const noexcept override { return pacer_.lastSleepNs(); }

    /// Renders frame `index` into `out` (same size, RGB24); false when `out` does not fit. Used by
    /// next() and by tests that need the picture of a given index.
    bool renderFrame(std::uint64_t index, vision::ImageView out) const noexcept;

    /// Scene time of a frame index, in seconds (1/30 s per index).
    static constexpr double sceneTime(std::uint64_t index) noexcept
    {
        return static_cast<double>(index) / 30.0;
    }

private:
    void renderBackground() noexcept;

    int width_;
    int height_;
    vision::ImageBuffer background_;
    vision::ImageBuffer frame_;
    FramePacer pacer_;
    std::uint64_t sequence_ = 0;
    char description_[96] = {};
};

}  // namespace platform
