#pragma once
// ChromaticityStage: fills FrameState::chroma with the r, g, b chromaticity planes (§1-§2).

#include "vision/chromaticity.hpp"
#include "vision/stage.hpp"

#include <memory>

namespace vision {

class ChromaticityStage final : public Stage {
public:
    /// Allocates the table and three planes of this size.
    explicit ChromaticityStage(Size size);
    const char* name() const noexcept override { return "chromaticity"; }
    void process(FrameState& state) noexcept override;

private:
    std::unique_ptr<ChromaticityTable> table_;  // 196 KiB: on the heap, not the stack
    ImageBuffer r_, g_, b_;
};

}  // namespace vision
