#pragma once
// FrameCheckStage: the pipeline's first stage. It passes good frames through untouched (no copy)
// and marks frames the rest of the pipeline must not read (no data, wrong size or format, a stride
// too small for the width): a misbehaving source must never make a tracker read out of bounds.

#include "vision/stage.hpp"

namespace vision {

class FrameCheckStage final : public Stage {
public:
    FrameCheckStage(Size expected, PixelFormat format) noexcept
        : expected_(expected), format_(format)
    {
    }
    const char* name() const noexcept override { return "check"; }
    void process(FrameState& state) noexcept override;

private:
    Size expected_;
    PixelFormat format_;
};

}  // namespace vision
