#pragma once
// Pipeline: the ordered vision stages, built at start-up. The firmware runs them one by one so it
// can time each; run() is for callers that do not need timing (tools, tests).

#include "vision/stage.hpp"

#include <array>
#include <cstddef>
#include <memory>

namespace vision {

class Pipeline {
public:
    static constexpr std::size_t kMaxStages = 16;

    /// Appends a stage (start-up only). Throws std::length_error past kMaxStages.
    void add(std::unique_ptr<Stage> stage);
    std::size_t size() const noexcept { return count_; }
    Stage& stage(std::size_t i) noexcept { return *stages_[i]; }

    /// Resets the per-frame state for a new frame.
    static void begin(FrameState& state, const Frame& frame) noexcept;
    /// Runs every stage; stops early when a stage marks the frame invalid.
    void run(FrameState& state) noexcept;

private:
    std::array<std::unique_ptr<Stage>, kMaxStages> stages_;
    std::size_t count_ = 0;
};

}  // namespace vision
