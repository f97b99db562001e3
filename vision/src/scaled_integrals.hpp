#pragma once
// ScaledIntegrals: one scale of FaceDetector's scan (METHOD.md §3): the frame shrunk with OpenCV's
// bit-exact bilinear resize (INTER_LINEAR_EXACT) and the integral tables the cascade reads.
// Buffers are sized once for the largest frame; prepare() never allocates.

#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <vector>

namespace vision {

class ScaledIntegrals {
public:
    /// Buffers for frames up to `maxFrameSize`; with `splitTable`, also for the
    /// column-deinterleaved sum tables (2 and 4 ways).
    ScaledIntegrals(Size maxFrameSize, bool splitTable);

    /// Shrinks the Gray8 `gray` to dw x dh (at most its size) and builds the sum and squared
    /// sum tables; with `split`, also the column-deinterleaved sum table, with `split4` the
    /// one deinterleaved 4 ways.
    void prepare(const ConstImageView& gray, int dw, int dh, bool split,
                 bool split4 = false) noexcept;

    /// The same built lazily, only where windows are evaluated: begin() takes the frame and the
    /// scale (no rows yet; `gray` must outlive the rows' preparation), prepareRows(top, bottom)
    /// makes table rows top..bottom (clipped to dh) valid for windows lying within them. Rows
    /// are asked for top-down; a window sum taken from them equals prepare()'s (the tables may
    /// count from a later row than 0: the difference cancels in every rectangle's four corners).
    /// With `split4`, the table deinterleaved 4 ways is built too.
    void begin(const ConstImageView& gray, int dw, int dh, bool split,
               bool split4 = false) noexcept;
    void prepareRows(int top, int bottom) noexcept;

    /// Entries per table row: maxFrameSize.width + 1.
    int stride() const noexcept { return stride_; }
    /// Sums over [0, x) x [0, y) at y * stride() + x, for 0 <= x <= dw, 0 <= y <= dh.
    const std::int32_t* sum() const noexcept { return sum_.data(); }
    /// Squared sums, wrapping in 32 bits like OpenCV's table (window sums stay exact).
    const std::uint32_t* squaredSum() const noexcept { return sqsum_.data(); }
    /// `sum()` with each row's even columns first, then the odd ones from (stride() + 1) / 2 on:
    /// the windows of a step-2 row are consecutive entries.
    const std::int32_t* splitSum() const noexcept { return sumSplit_.data(); }
    /// `sum()` with each row's columns 4 ways: those of x mod 4 = m from m * ((stride() + 3) /
    /// 4) on, so windows 4 px apart are consecutive entries; rows split4Stride() apart.
    const std::int32_t* split4Sum() const noexcept { return sumSplit4_.data(); }
    int split4Stride() const noexcept { return 4 * ((stride_ + 3) / 4); }

private:
    void shrinkRow(int y) noexcept;
    void integrateRow(int y) noexcept;
    void deinterleaveRow(int y) noexcept;
    void deinterleave4Row(int y) noexcept;
    void zeroRow(int y) noexcept;

    int stride_ = 0;
    int scaledStride_ = 0;
    ConstImageView gray_{};  ///< the frame being prepared (begin())
    int dw_ = 0, dh_ = 0;
    bool split_ = false;
    bool split4_ = false;
    int origin_ = -1;  ///< table row counted from (all zero); -1: no rows prepared
    int ready_ = -1;   ///< table rows origin_..ready_ are valid
    std::vector<std::uint8_t> scaled_;
    std::vector<std::int32_t> sum_;
    std::vector<std::uint32_t> sqsum_;
    std::vector<std::int32_t> sumSplit_;
    std::vector<std::int32_t> sumSplit4_;
    std::vector<int> xofs0_, xofs1_, yofs0_, yofs1_;
    std::vector<std::int32_t> xw0_, xw1_, yw0_, yw1_;
    /// The resize's vertical pass of the two source rows of the shrunk row being made.
    std::vector<std::uint16_t> vertical_;
};

}  // namespace vision
