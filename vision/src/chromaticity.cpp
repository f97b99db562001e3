#include "vision/chromaticity.hpp"

#include "chromaticity_kernels.hpp"
#include "simd.hpp"
#include "vision/yuv.hpp"

// Why the SIMD paths are exact (chromaticity_kernels.hpp has the arithmetic). Let c <= sum, s1 =
// max(sum, 1) and q = floor((510 c + sum) / (2 sum)) the wanted value (0 for sum = 0).
//  0. n = 255 c + floor(sum / 2) < 2^16 and q = floor(n / s1): for even sum the fractions are
//     equal; for odd sum, (255 c + sum/2) / sum only adds 1/(2 sum) to (255 c + (sum-1)/2) / sum,
//     whose numerator is an integer, so it cannot reach the next multiple of sum. For sum = 0,
//     c = n = 0.
//  1. m = min(trunc(65536 / s1), 65535) = 65536 / s1 + dm with dm in (-1, 0]: if 65536 / s1 is
//     not an integer it is at least 1 / s1 away from one, more than the float reciprocal's error
//     (< 65536 / s1 * 2^-21 after the Newton step, 0.5 ulp for a true division), so truncation is
//     exact; if it is an integer the truncation may give one less (dm = -1), and s1 = 1 gives
//     65535 (dm = -1). dm = -1 cases have n < 65536, so n dm / 65536 > -1 in every case.
//  2. q0 = floor(n m / 65536) = floor(n / s1 + n dm / 65536) is therefore q or q - 1.
//  3. d = n - s1 q0 is then in [0, 2 s1) (< 1530): 16-bit wrapping arithmetic gives it exactly,
//     and q = q0 + (d >= s1) is the definition of the floor.
// ChromaticitySimd.EveryPairExact checks all 256 x 766 (c, sum) pairs through each kernel.

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

namespace chroma_detail {
namespace {

/// One pixel: select the table row of its sum once, then one look-up per channel (§2,
/// dissertation 4.3).
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
void convertRow(const ChromaticityTable& table, const std::uint8_t* p, int w, std::uint8_t* pr,
                std::uint8_t* pg, std::uint8_t* pb) noexcept
{
    int x = 0;
    // §2 (dissertation 4.3): unrolled by four, one table row pointer per pixel, no divides or
    // branches.
    for (; x + 4 <= w; x += 4, p += 4 * Step) {
        convertPixel<R, G, B>(table, p, pr + x, pg + x, pb + x);
        convertPixel<R, G, B>(table, p + Step, pr + x + 1, pg + x + 1, pb + x + 1);
        convertPixel<R, G, B>(table, p + 2 * Step, pr + x + 2, pg + x + 2, pb + x + 2);
        convertPixel<R, G, B>(table, p + 3 * Step, pr + x + 3, pg + x + 3, pb + x + 3);
    }
    for (; x < w; ++x, p += Step)
        convertPixel<R, G, B>(table, p, pr + x, pg + x, pb + x);
}

void rowScalar(const ChromaticityTable& table, const std::uint8_t* src, int n, Packing packing,
               std::uint8_t* r, std::uint8_t* g, std::uint8_t* b) noexcept
{
    // Channel offsets as template arguments so the unrolled body has constant addressing.
    switch (packing) {
        case Packing::Rgb24:
            convertRow<0, 1, 2, 3>(table, src, n, r, g, b);
            break;
        case Packing::Bgr24:
            convertRow<2, 1, 0, 3>(table, src, n, r, g, b);
            break;
        case Packing::Xrgb8888:
            convertRow<2, 1, 0, 4>(table, src, n, r, g, b);
            break;
    }
}

}  // namespace
}  // namespace chroma_detail

namespace {

using chroma_detail::Packing;
using chroma_detail::RowKernel;

bool planeFits(const ImageView& plane, const ConstImageView& in) noexcept
{
    return !plane.empty() && plane.format == PixelFormat::Gray8 && plane.width == in.width &&
           plane.height == in.height;
}

ChromaticityPath resolve(ChromaticityPath path) noexcept
{
    return path == ChromaticityPath::Best ? bestChromaticityPath() : path;
}

RowKernel rowKernel(ChromaticityPath path) noexcept
{
    switch (resolve(path)) {
        case ChromaticityPath::Scalar:
            return chroma_detail::rowScalar;
#if defined(__x86_64__)
        case ChromaticityPath::Avx2:
            return simd::hasAvx2() ? chroma_detail::rowAvx2 : nullptr;
#endif
#if defined(__aarch64__)
        case ChromaticityPath::Neon:
            return chroma_detail::rowNeon;
#endif
        default:
            return nullptr;
    }
}

/// Chunk of YUV pixels converted to RGB on the stack at a time (even; 768 bytes).
constexpr int kYuvChunk = 256;

}  // namespace

const char* chromaticityPathName(ChromaticityPath path) noexcept
{
    switch (path) {
        case ChromaticityPath::Scalar:
            return "scalar";
        case ChromaticityPath::Avx2:
            return "avx2";
        case ChromaticityPath::Neon:
            return "neon";
        case ChromaticityPath::Best:
            return "best";
    }
    return "?";
}

bool chromaticityPathAvailable(ChromaticityPath path) noexcept
{
    return rowKernel(path) != nullptr;
}

ChromaticityPath bestChromaticityPath() noexcept
{
#if defined(__x86_64__)
    return simd::hasAvx2() ? ChromaticityPath::Avx2 : ChromaticityPath::Scalar;
#elif defined(__aarch64__)
    return ChromaticityPath::Neon;
#else
    return ChromaticityPath::Scalar;
#endif
}

bool convertChromaticity(const ChromaticityTable& table, const ConstImageView& input,
                         const ChromaticityPlanes& output, ChromaticityPath path) noexcept
{
    const RowKernel kernel = rowKernel(path);
    if (kernel == nullptr || input.empty() || !planeFits(output.r, input) ||
        !planeFits(output.g, input) || !planeFits(output.b, input))
        return false;
    const int w = input.width;
    switch (input.format) {
        case PixelFormat::RGB24:
        case PixelFormat::BGR24:
        case PixelFormat::XRGB8888: {
            const Packing packing = input.format == PixelFormat::RGB24   ? Packing::Rgb24
                                    : input.format == PixelFormat::BGR24 ? Packing::Bgr24
                                                                         : Packing::Xrgb8888;
            for (int y = 0; y < input.height; ++y)
                kernel(table, input.row(y), w, packing, output.r.row(y), output.g.row(y),
                       output.b.row(y));
            return true;
        }
        case PixelFormat::YUYV:
        case PixelFormat::NV12: {
            if (!convertibleToRgb24(input))
                return false;
            std::uint8_t rgb[kYuvChunk * 3];
            const std::uint8_t* uvPlane =
                input.data + static_cast<std::ptrdiff_t>(input.stride) * input.height;
            for (int y = 0; y < input.height; ++y) {
                for (int x0 = 0; x0 < w; x0 += kYuvChunk) {
                    const int n = w - x0 < kYuvChunk ? w - x0 : kYuvChunk;
                    if (input.format == PixelFormat::YUYV)
                        yuyvRowToRgb24(input.row(y), x0, n, rgb);
                    else
                        nv12RowToRgb24(input.row(y),
                                       uvPlane + static_cast<std::ptrdiff_t>(y / 2) * input.stride,
                                       x0, n, rgb);
                    kernel(table, rgb, n, Packing::Rgb24, output.r.row(y) + x0,
                           output.g.row(y) + x0, output.b.row(y) + x0);
                }
            }
            return true;
        }
        case PixelFormat::Gray8:
            return false;
    }
    return false;
}

bool convertChromaticity(const ChromaticityTable& table, const ConstImageView& input,
                         const ChromaticityPlanes& output) noexcept
{
    return convertChromaticity(table, input, output, ChromaticityPath::Best);
}

bool chromaticityQuotients(const ChromaticityTable& table, ChromaticityPath path,
                           const std::uint16_t* c, const std::uint16_t* sum, std::uint8_t* out,
                           int n) noexcept
{
    switch (resolve(path)) {
        case ChromaticityPath::Scalar:
            for (int i = 0; i < n; ++i)
                out[i] = table.row(sum[i])[c[i]];
            return true;
#if defined(__x86_64__)
        case ChromaticityPath::Avx2:
            if (!simd::hasAvx2())
                return false;
            chroma_detail::quotientsAvx2(c, sum, out, n);
            return true;
#endif
#if defined(__aarch64__)
        case ChromaticityPath::Neon:
            chroma_detail::quotientsNeon(c, sum, out, n);
            return true;
#endif
        default:
            return false;
    }
}

}  // namespace vision
