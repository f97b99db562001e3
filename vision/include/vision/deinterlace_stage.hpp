#pragma once
// DeinterlaceStage: removes interlace tearing (§2, deinterlace.hpp) before any other stage
// looks at the frame. The camera's buffer is read-only to the pipeline, so the stage writes into
// its own frame buffer (allocated in the constructor) and replaces FrameState::frame.image with a
// view of it; later stages and the renderer then see the deinterlaced frame. Switched on in the
// firmware's config; put it first (after the frame check).

#include "vision/image.hpp"
#include "vision/stage.hpp"

namespace vision {

class DeinterlaceStage final : public Stage {
public:
    /// Allocates one frame of this size and format. Throws std::invalid_argument as ImageBuffer.
    DeinterlaceStage(Size size, PixelFormat format);
    const char* name() const noexcept override { return "deinterlace"; }
    /// Marks the frame invalid if its size or format differs from the constructor's.
    void process(FrameState& state) noexcept override;

private:
    ImageBuffer frame_;
};

}  // namespace vision
