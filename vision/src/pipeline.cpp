#include "vision/pipeline.hpp"

#include <stdexcept>

namespace vision {

void Pipeline::add(std::unique_ptr<Stage> stage)
{
    if (count_ == kMaxStages)
        throw std::length_error("vision pipeline: too many stages");
    stages_[count_++] = std::move(stage);
}

void Pipeline::begin(FrameState& state, const Frame& frame) noexcept
{
    state = FrameState{};
    state.frame = frame;
}

void Pipeline::run(FrameState& state) noexcept
{
    for (std::size_t i = 0; i < count_ && state.valid; ++i)
        stages_[i]->process(state);
}

}  // namespace vision
