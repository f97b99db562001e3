#include "vision/chromaticity.hpp"

namespace vision {

std::uint8_t ChromaticityTable::exact(int c, int sum) noexcept
{
    if (sum <= 0)
        return 0;
    // round(255 c / sum), halves up, in integers: floor((510 c + sum) / (2 sum)).
    return static_cast<std::uint8_t>((510 * c + sum) / (2 * sum));
}

ChromaticityTable::ChromaticityTable()
{
    for (int sum = 0; sum < kSums; ++sum)
        for (int c = 0; c < 256; ++c)
            // Entries with c > sum never occur for real pixels; clamp them so the table is total.
            table_[static_cast<std::size_t>(sum) * 256 + c] = exact(c <= sum ? c : sum, sum);
}

namespace {

/// Channel byte offsets of R, G, B within one pixel.
struct Layout {
    int r, g, b, step;
};

bool layoutOf(PixelFormat f, Layout& out) noexcept
{
    switch (f) {
        case PixelFormat::RGB24:
            out = {0, 1, 2, 3};
            return true;
        case PixelFormat::BGR24:
            out = {2, 1, 0, 3};
            return true;
        case PixelFormat::XRGB8888:
            out = {2, 1, 0, 4};
            return true;
        default:
            return false;
    }
}

/// One pixel: select the table row of its sum once, then one look-up per channel (4.3).
template <int R, int G, int B>
inline void convertPixel(const ChromaticityTable& table, const std::uint8_t* q, std::uint8_t* r,
                         std::uint8_t* g, std::uint8_t* b) noexcept
{
    const std::uint8_t* t = table.row(q[R] + q[G] + q[B]);
    *r = t[q[R]];
    *g = t[q[G]];
    *b = t[q[B]];
}

template <int R, int G, int B, int Step>
void convertRows(const ChromaticityTable& table, const ConstImageView& in,
                 const ChromaticityPlanes& out) noexcept
{
    const int w = in.width;
    for (int y = 0; y < in.height; ++y) {
        const std::uint8_t* p = in.row(y);
        std::uint8_t* pr = out.r.row(y);
        std::uint8_t* pg = out.g.row(y);
        std::uint8_t* pb = out.b.row(y);
        int x = 0;
        // 4.3: unrolled by four, one table row pointer per pixel, no divides or branches.
        for (; x + 4 <= w; x += 4, p += 4 * Step) {
            convertPixel<R, G, B>(table, p, pr + x, pg + x, pb + x);
            convertPixel<R, G, B>(table, p + Step, pr + x + 1, pg + x + 1, pb + x + 1);
            convertPixel<R, G, B>(table, p + 2 * Step, pr + x + 2, pg + x + 2, pb + x + 2);
            convertPixel<R, G, B>(table, p + 3 * Step, pr + x + 3, pg + x + 3, pb + x + 3);
        }
        for (; x < w; ++x, p += Step)
            convertPixel<R, G, B>(table, p, pr + x, pg + x, pb + x);
    }
}

bool planeFits(const ImageView& plane, const ConstImageView& in) noexcept
{
    return !plane.empty() && plane.format == PixelFormat::Gray8 && plane.width == in.width &&
           plane.height == in.height;
}

}  // namespace

bool convertChromaticity(const ChromaticityTable& table, const ConstImageView& input,
                         const ChromaticityPlanes& output) noexcept
{
    Layout l{};
    if (input.empty() || !layoutOf(input.format, l) || !planeFits(output.r, input) ||
        !planeFits(output.g, input) || !planeFits(output.b, input))
        return false;
    // Channel offsets as template arguments so the unrolled body has constant addressing.
    if (l.step == 4)
        convertRows<2, 1, 0, 4>(table, input, output);
    else if (l.r == 0)
        convertRows<0, 1, 2, 3>(table, input, output);
    else
        convertRows<2, 1, 0, 3>(table, input, output);
    return true;
}

}  // namespace vision
