#include "vision/yuv.hpp"

#include <array>
#include <cstring>

namespace vision {

namespace {

/// The products of the formula in yuv.hpp, indexed by the 8-bit sample.
struct YuvTables {
    std::array<std::int32_t, 256> y;   ///< 298 (Y - 16) + 128 (the rounding term folded in)
    std::array<std::int32_t, 256> rv;  ///< 409 (V - 128)
    std::array<std::int32_t, 256> gu;  ///< -100 (U - 128)
    std::array<std::int32_t, 256> gv;  ///< -208 (V - 128)
    std::array<std::int32_t, 256> bu;  ///< 516 (U - 128)
};

constexpr YuvTables makeTables()
{
    YuvTables t{};
    for (int i = 0; i < 256; ++i) {
        const auto k = static_cast<std::size_t>(i);
        t.y[k] = 298 * (i - 16) + 128;
        t.rv[k] = 409 * (i - 128);
        t.gu[k] = -100 * (i - 128);
        t.gv[k] = -208 * (i - 128);
        t.bu[k] = 516 * (i - 128);
    }
    return t;
}

constexpr YuvTables kTables = makeTables();

inline std::uint8_t clamp255(std::int32_t v) noexcept
{
    v >>= 8;
    return static_cast<std::uint8_t>(v < 0 ? 0 : (v > 255 ? 255 : v));
}

/// Two pixels sharing one U,V pair.
inline void pair(int y0, int y1, int u, int v, std::uint8_t* out) noexcept
{
    const std::int32_t r = kTables.rv[static_cast<std::size_t>(v)];
    const std::int32_t g =
        kTables.gu[static_cast<std::size_t>(u)] + kTables.gv[static_cast<std::size_t>(v)];
    const std::int32_t b = kTables.bu[static_cast<std::size_t>(u)];
    const std::int32_t l0 = kTables.y[static_cast<std::size_t>(y0)];
    const std::int32_t l1 = kTables.y[static_cast<std::size_t>(y1)];
    out[0] = clamp255(l0 + r);
    out[1] = clamp255(l0 + g);
    out[2] = clamp255(l0 + b);
    out[3] = clamp255(l1 + r);
    out[4] = clamp255(l1 + g);
    out[5] = clamp255(l1 + b);
}

}  // namespace

Rgb8 yuvToRgb(int y, int u, int v) noexcept
{
    const int c = y - 16, d = u - 128, e = v - 128;
    return {clamp255(298 * c + 409 * e + 128), clamp255(298 * c - 100 * d - 208 * e + 128),
            clamp255(298 * c + 516 * d + 128)};
}

void yuyvRowToRgb24(const std::uint8_t* yuyvRow, int x0, int n, std::uint8_t* out) noexcept
{
    const std::uint8_t* p = yuyvRow + 2 * x0;
    for (int x = 0; x < n; x += 2, p += 4, out += 6)
        pair(p[0], p[2], p[1], p[3], out);
}

void nv12RowToRgb24(const std::uint8_t* yRow, const std::uint8_t* uvRow, int x0, int n,
                    std::uint8_t* out) noexcept
{
    const std::uint8_t* py = yRow + x0;
    const std::uint8_t* puv = uvRow + x0;  // one U,V byte pair per two pixels: same offset
    for (int x = 0; x < n; x += 2, py += 2, puv += 2, out += 6)
        pair(py[0], py[1], puv[0], puv[1], out);
}

bool convertibleToRgb24(const ConstImageView& in) noexcept
{
    if (in.empty())
        return false;
    switch (in.format) {
        case PixelFormat::YUYV:
            return in.width % 2 == 0;
        case PixelFormat::NV12:
            return in.width % 2 == 0 && in.height % 2 == 0;
        case PixelFormat::XRGB8888:
        case PixelFormat::BGR24:
        case PixelFormat::RGB24:
            return true;
        case PixelFormat::Gray8:
            return false;
    }
    return false;
}

bool convertToRgb24(const ConstImageView& in, const ImageView& out) noexcept
{
    if (!convertibleToRgb24(in) || out.empty() || out.format != PixelFormat::RGB24 ||
        out.size() != in.size())
        return false;
    const int w = in.width;
    for (int y = 0; y < in.height; ++y) {
        const std::uint8_t* p = in.row(y);
        std::uint8_t* o = out.row(y);
        switch (in.format) {
            case PixelFormat::YUYV:
                yuyvRowToRgb24(p, 0, w, o);
                break;
            case PixelFormat::NV12:
                nv12RowToRgb24(p,
                               in.data + static_cast<std::ptrdiff_t>(in.stride) * in.height +
                                   static_cast<std::ptrdiff_t>(y / 2) * in.stride,
                               0, w, o);
                break;
            case PixelFormat::XRGB8888:
                for (int x = 0; x < w; ++x, p += 4, o += 3) {
                    o[0] = p[2];
                    o[1] = p[1];
                    o[2] = p[0];
                }
                break;
            case PixelFormat::BGR24:
                for (int x = 0; x < w; ++x, p += 3, o += 3) {
                    o[0] = p[2];
                    o[1] = p[1];
                    o[2] = p[0];
                }
                break;
            case PixelFormat::RGB24:
                std::memcpy(o, p, static_cast<std::size_t>(w) * 3);
                break;
            case PixelFormat::Gray8:
                break;
        }
    }
    return true;
}

}  // namespace vision
