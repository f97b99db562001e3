#pragma once
// RowPrefilter: the first stages of FaceDetector's cascade (METHOD.md §3) for a whole row of
// windows at once, one weak classifier over consecutive windows (SIMD), while enough of the row
// is alive; the windows it cannot decide go on one at a time (FixedCascade::evaluate). Its
// decisions are those of the exact path. Buffers are sized once; run() never allocates.

#include "fixed_cascade.hpp"
#include "scaled_integrals.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vision {

class RowPrefilter {
public:
    /// Rows with fewer windows to evaluate than this are not worth prefiltering.
    static constexpr int kMinWindows = 4;

    /// Buffers for rows of up to `maxWindows` windows.
    explicit RowPrefilter(int maxWindows);

    /// Evaluates stages 0.. of the windows j0 <= j < j1 of row y (window j at x = j * step) of
    /// `tables` (prepared with the split table when step is 2, the one split 4 ways when 4) for a
    /// cascade with a row form.
    /// `wanted` (null: every window), indexed by j: only windows with wanted[j] != 0 are
    /// evaluated (the others' result is -1, never to be read): a masked scan's rows are mostly
    /// windows it does not want. Returns how many stages were done; then result(j) and from(j)
    /// tell each wanted window's state.
    /// With `endStage` >= 0, stages from endStage on are not done.
    int run(const FixedCascade& cascade, const ScaledIntegrals& tables, int y, int step, int j0,
            int j1, const std::uint8_t* wanted = nullptr, int endStage = -1) noexcept;

    /// Window j after run(): 1 when it passed the stages done, 2 when a stage sum was too close
    /// to its threshold (the exact path continues from stage from(j)), else
    /// FixedCascade::evaluate's value.
    int result(int j) const noexcept { return result_[static_cast<std::size_t>(j)]; }
    int from(int j) const noexcept { return from_[static_cast<std::size_t>(j)]; }

private:
    std::vector<float> norm_;        // per window: vnf, 0 when flat
    std::vector<std::int32_t> acc_;  // stage sums, Q20
    std::vector<int> result_;
    std::vector<int> from_;
};

}  // namespace vision
