// One scale of the scan: OpenCV's bit-exact bilinear resize and the integral tables.
//
// As cv::CascadeClassifier::detectMultiScale (OpenCV 4.6), the image is shrunk per scale to
// round(size / scale) with resize(INTER_LINEAR_EXACT): source positions from the double scale,
// 8-bit fractional weights rounded per axis, the vertical pass rounded once at the end. The sum
// table is 32-bit, the squared sum table wraps in 32 bits as OpenCV's does (window sums, taken
// as differences, stay exact).

#include "scaled_integrals.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vision {
namespace {

constexpr int kResizeShift = 8;  // INTER_LINEAR_EXACT weights for 8-bit images

// Per-scale tables of the bit-exact bilinear resize along one axis: source offsets and weights.
struct ResizeAxis {
    int* ofs0;
    int* ofs1;
    std::int32_t* w0;
    std::int32_t* w1;
};

void resizeTable(int srcSize, int dstSize, ResizeAxis t) noexcept
{
    // OpenCV: inv_scale = dst / src (double); scale = 1 / inv_scale; fval = scale * (d + 0.5) -
    // 0.5; weights rounded to 1/256, the first weight being 256 minus the second.
    const double invScale = static_cast<double>(dstSize) / static_cast<double>(srcSize);
    const double scale = 1.0 / invScale;
    for (int d = 0; d < dstSize; ++d) {
        const double fval = scale * (static_cast<double>(d) + 0.5) - 0.5;
        const int ival = static_cast<int>(std::floor(fval));
        if (ival >= 0 && srcSize > 1 && ival < srcSize - 1) {
            const int w1 = static_cast<int>(
                std::nearbyint((fval - static_cast<double>(ival)) * (1 << kResizeShift)));
            t.ofs0[d] = ival;
            t.ofs1[d] = ival + 1;
            t.w1[d] = w1;
            t.w0[d] = (1 << kResizeShift) - w1;
        } else {
            const int edge = ival < 0 || srcSize <= 1 ? 0 : srcSize - 1;
            t.ofs0[d] = edge;
            t.ofs1[d] = edge;
            t.w0[d] = 1 << kResizeShift;
            t.w1[d] = 0;
        }
    }
}

}  // namespace

ScaledIntegrals::ScaledIntegrals(Size maxFrameSize, bool splitTable)
    : stride_(maxFrameSize.width + 1), scaledStride_(maxFrameSize.width)
{
    const auto maxW = static_cast<std::size_t>(maxFrameSize.width);
    const auto maxH = static_cast<std::size_t>(maxFrameSize.height);
    scaled_.assign(maxW * maxH, 0);
    // Row 0 and column 0 of the tables stay zero.
    sum_.assign((maxW + 1) * (maxH + 1), 0);
    sqsum_.assign((maxW + 1) * (maxH + 1), 0);
    if (splitTable) {
        sumSplit_.assign((maxW + 1) * (maxH + 1), 0);
        sumSplit4_.assign(static_cast<std::size_t>(split4Stride()) * (maxH + 1), 0);
    }
    for (auto* v : {&xofs0_, &xofs1_})
        v->assign(maxW, 0);
    for (auto* v : {&yofs0_, &yofs1_})
        v->assign(maxH, 0);
    for (auto* v : {&xw0_, &xw1_})
        v->assign(maxW, 0);
    for (auto* v : {&yw0_, &yw1_})
        v->assign(maxH, 0);
    vertical_.assign(maxW + 1, 0);
}

void ScaledIntegrals::prepare(const ConstImageView& gray, int dw, int dh, bool split,
                              bool split4) noexcept
{
    begin(gray, dw, dh, split, split4);
    prepareRows(0, dh);
}

void ScaledIntegrals::begin(const ConstImageView& gray, int dw, int dh, bool split,
                            bool split4) noexcept
{
    split4_ = split4;
    gray_ = gray;
    dw_ = dw;
    dh_ = dh;
    split_ = split;
    origin_ = -1;
    ready_ = -1;
    resizeTable(gray.width, dw, {xofs0_.data(), xofs1_.data(), xw0_.data(), xw1_.data()});
    resizeTable(gray.height, dh, {yofs0_.data(), yofs1_.data(), yw0_.data(), yw1_.data()});
}

void ScaledIntegrals::prepareRows(int top, int bottom) noexcept
{
    // §3: the scan asks for the rows of the windows it evaluates; a masked or budgeted scan
    // touches a band of each scale, and rows above the band are never shrunk nor summed. Table
    // row `top` then counts as row 0 (all zero): a rectangle's sum from four corners is the same
    // (modulo 2^32, as the tables wrap anyway).
    bottom = std::min(bottom, dh_);
    top = std::max(top, 0);
    if (top > bottom)
        return;
    if (origin_ < 0 || top < origin_ || top > ready_) {
        origin_ = top;
        ready_ = top;
        zeroRow(top);
    }
    for (int y = ready_; y < bottom; ++y) {
        shrinkRow(y);
        integrateRow(y);
        if (split_)
            deinterleaveRow(y + 1);
        if (split4_)
            deinterleave4Row(y + 1);
    }
    ready_ = std::max(ready_, bottom);
}

void ScaledIntegrals::zeroRow(int y) noexcept
{
    const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(y) * stride_;
    std::fill_n(sum_.data() + at, dw_ + 1, 0);
    std::fill_n(sqsum_.data() + at, dw_ + 1, 0u);
    if (split_)
        deinterleaveRow(y);
    if (split4_)
        deinterleave4Row(y);
}

void ScaledIntegrals::shrinkRow(int y) noexcept
{
    std::uint8_t* out = scaled_.data() + static_cast<std::ptrdiff_t>(y) * scaledStride_;
    const int dw = dw_;
    if (dw == gray_.width && dh_ == gray_.height) {
        std::memcpy(out, gray_.row(y), static_cast<std::size_t>(dw));
        return;
    }
    // OpenCV's order is the horizontal pass of each source row, then the vertical pass; both
    // are exact integer sums with the 8-bit weights (a + b = 256, c0 + c1 = 256), so the
    // vertical pass first gives the same integers: a * (c0 r0[x0] + c1 r0[x1]) +
    // b * (c0 r1[x0] + c1 r1[x1]) = c0 (a r0[x0] + b r1[x0]) + c1 (a r0[x1] + b r1[x1]). The
    // vertical pass runs over whole source rows (a loop the compiler vectorises), the
    // gathering horizontal pass once per shrunk row instead of once per source row.
    const std::uint8_t* __restrict r0 = gray_.row(yofs0_[static_cast<std::size_t>(y)]);
    const std::uint8_t* __restrict r1 = gray_.row(yofs1_[static_cast<std::size_t>(y)]);
    const auto a = static_cast<std::uint16_t>(yw0_[static_cast<std::size_t>(y)]);
    const auto b = static_cast<std::uint16_t>(yw1_[static_cast<std::size_t>(y)]);
    // At most 255 x 256: 16 bits.
    std::uint16_t* __restrict v = vertical_.data();
    const int width = gray_.width;
    for (int x = 0; x < width; ++x)
        v[x] = static_cast<std::uint16_t>(r0[x] * a + r1[x] * b);
    v[width] = 0;  // read with weight 0 beside the last column
    // The second source column is the first's neighbour (or the first itself at an edge, with
    // weight 0), and c0 = 256 - c1: c0 p + c1 q = 256 p + c1 (q - p).
    // (Plain pointers: a byte stored through `out` could otherwise alias the vectors'.)
    const int* __restrict ofs = xofs0_.data();
    const std::int32_t* __restrict weight = xw1_.data();
    std::uint8_t* __restrict shrunk = out;
    for (int x = 0; x < dw; ++x) {
        const std::uint16_t* pair = v + ofs[x];
        const std::int32_t p = pair[0];
        const std::int32_t q = pair[1];
        shrunk[x] = static_cast<std::uint8_t>((p * 256 + (q - p) * weight[x] + (1 << 15)) >> 16);
    }
}

void ScaledIntegrals::integrateRow(int y) noexcept
{
    // Scaled row y into table row y + 1.
    const std::uint8_t* in = scaled_.data() + static_cast<std::ptrdiff_t>(y) * scaledStride_;
    std::int32_t* s1 = sum_.data() + static_cast<std::ptrdiff_t>(y + 1) * stride_ + 1;
    const std::int32_t* s0 = s1 - stride_;
    std::uint32_t* q1 = sqsum_.data() + static_cast<std::ptrdiff_t>(y + 1) * stride_ + 1;
    const std::uint32_t* q0 = q1 - stride_;
    std::uint32_t rs = 0;
    std::uint32_t rq = 0;
    for (int x = 0; x < dw_; ++x) {
        const std::uint32_t v = in[x];
        // Both tables wrap modulo 2^32 past 8.4 Mpx (like OpenCV's 32-bit ones), in unsigned
        // arithmetic where that is defined: a window's sum taken from them stays exact.
        rs += v;
        rq += v * v;
        s1[x] = static_cast<std::int32_t>(static_cast<std::uint32_t>(s0[x]) + rs);
        q1[x] = q0[x] + rq;
    }
}

void ScaledIntegrals::deinterleaveRow(int y) noexcept
{
    const int dw = dw_;
    const int half = (stride_ + 1) / 2;
    const std::int32_t* __restrict in = sum_.data() + static_cast<std::ptrdiff_t>(y) * stride_;
    std::int32_t* __restrict even = sumSplit_.data() + static_cast<std::ptrdiff_t>(y) * stride_;
    std::int32_t* __restrict odd = even + half;
    // Pairs of columns: a loop the compiler vectorises (the tables do not overlap).
    for (int i = 0; i < (dw + 1) / 2; ++i) {
        even[i] = in[2 * i];
        odd[i] = in[2 * i + 1];
    }
    if ((dw & 1) == 0)
        even[dw >> 1] = in[dw];
}

void ScaledIntegrals::deinterleave4Row(int y) noexcept
{
    const int entries = dw_ + 1;  // columns 0..dw
    const int quarter = (stride_ + 3) / 4;
    const std::int32_t* __restrict in = sum_.data() + static_cast<std::ptrdiff_t>(y) * stride_;
    std::int32_t* __restrict p0 =
        sumSplit4_.data() + static_cast<std::ptrdiff_t>(y) * split4Stride();
    std::int32_t* __restrict p1 = p0 + quarter;
    std::int32_t* __restrict p2 = p1 + quarter;
    std::int32_t* __restrict p3 = p2 + quarter;
    // Groups of four columns (a loop the compiler vectorises), then the last few.
    const int groups = entries / 4;
    for (int i = 0; i < groups; ++i) {
        p0[i] = in[4 * i];
        p1[i] = in[4 * i + 1];
        p2[i] = in[4 * i + 2];
        p3[i] = in[4 * i + 3];
    }
    std::int32_t* const parts[4] = {p0, p1, p2, p3};
    for (int x = 4 * groups; x < entries; ++x)
        parts[x & 3][x >> 2] = in[x];
}

}  // namespace vision
