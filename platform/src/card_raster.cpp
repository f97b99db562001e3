#include "platform/card_raster.hpp"

#include "noise_hash.hpp"

#include <algorithm>
#include <cmath>

namespace platform {

void cardToImageHomography(const vision::Quad& quad, double m[9]) noexcept
{
    // Heckbert's unit square -> quad mapping ((0,0), (1,0), (1,1), (0,1) -> corners 0..3), then
    // s = (u + 1) / 2, t = (v + 1) / 2.
    const double x0 = quad[0].x, y0 = quad[0].y, x1 = quad[1].x, y1 = quad[1].y;
    const double x2 = quad[2].x, y2 = quad[2].y, x3 = quad[3].x, y3 = quad[3].y;
    const double dx1 = x1 - x2, dx2 = x3 - x2, dx3 = x0 - x1 + x2 - x3;
    const double dy1 = y1 - y2, dy2 = y3 - y2, dy3 = y0 - y1 + y2 - y3;
    const double den = dx1 * dy2 - dx2 * dy1;
    const double g = den != 0.0 ? (dx3 * dy2 - dx2 * dy3) / den : 0.0;
    const double h = den != 0.0 ? (dx1 * dy3 - dx3 * dy1) / den : 0.0;
    const double s[9] = {
        x1 - x0 + g * x1, x3 - x0 + h * x3, x0, y1 - y0 + g * y1, y3 - y0 + h * y3, y0, g, h, 1.0};
    for (int r = 0; r < 3; ++r) {
        m[3 * r + 0] = 0.5 * s[3 * r + 0];
        m[3 * r + 1] = 0.5 * s[3 * r + 1];
        m[3 * r + 2] = 0.5 * (s[3 * r + 0] + s[3 * r + 1]) + s[3 * r + 2];
    }
}

bool drawCardQuad(vision::ImageView image, const vision::Quad& quad,
                  const CardPaint& paint) noexcept
{
    const vision::RgbLayout layout = vision::rgbLayout(image.format);
    if (image.empty() || layout.bytesPerPixel == 0)
        return false;

    double m[9];
    cardToImageHomography(quad, m);
    // Pixel -> card coordinates: the adjugate (the scale of a homography does not matter).
    const double hinv[9] = {
        m[4] * m[8] - m[5] * m[7], m[2] * m[7] - m[1] * m[8], m[1] * m[5] - m[2] * m[4],
        m[5] * m[6] - m[3] * m[8], m[0] * m[8] - m[2] * m[6], m[2] * m[3] - m[0] * m[5],
        m[3] * m[7] - m[4] * m[6], m[1] * m[6] - m[0] * m[7], m[0] * m[4] - m[1] * m[3],
    };

    // Edge functions: signed distance in pixels, positive inside (the corners are clockwise on
    // screen, y down).
    double nx[4], ny[4], c0[4];
    double minX = 1e9, maxX = -1e9, minY = 1e9, maxY = -1e9;
    for (int i = 0; i < 4; ++i) {
        const double px = quad[i].x, py = quad[i].y;
        const double qx = quad[(i + 1) % 4].x, qy = quad[(i + 1) % 4].y;
        const double len = std::max(std::hypot(qx - px, qy - py), 1e-9);
        nx[i] = -(qy - py) / len;
        ny[i] = (qx - px) / len;
        c0[i] = -(nx[i] * px + ny[i] * py);
        minX = std::min(minX, px);
        maxX = std::max(maxX, px);
        minY = std::min(minY, py);
        maxY = std::max(maxY, py);
    }
    const double lastX = image.width - 1, lastY = image.height - 1;
    if (maxX < -1.0 || maxY < -1.0 || minX > lastX + 1.0 || minY > lastY + 1.0)
        return true;  // wholly outside
    const int x0 = static_cast<int>(std::max(0.0, std::floor(minX) - 1.0));
    const int x1 = static_cast<int>(std::min(lastX, std::ceil(maxX) + 1.0));
    const int y0 = static_cast<int>(std::max(0.0, std::floor(minY) - 1.0));
    const int y1 = static_cast<int>(std::min(lastY, std::ceil(maxY) + 1.0));

    // Subsample offsets of a 4x4 grid within the pixel; all samples lie within 0.54 px of the
    // centre, so pixels farther than that from every edge need no sampling.
    constexpr double kOffsets[4] = {-0.375, -0.125, 0.125, 0.375};
    constexpr double kSure = 0.54;
    const double base[3] = {static_cast<double>(paint.red), static_cast<double>(paint.green),
                            static_cast<double>(paint.blue)};
    const int noiseSpan = 2 * std::max(0, paint.noise) + 1;
    const int offsets[3] = {layout.r, layout.g, layout.b};

    for (int y = y0; y <= y1; ++y) {
        std::uint8_t* p = image.row(y) + static_cast<std::ptrdiff_t>(x0) * layout.bytesPerPixel;
        for (int x = x0; x <= x1; ++x, p += layout.bytesPerPixel) {
            double d[4];
            double dmin = 1e9;
            for (int i = 0; i < 4; ++i) {
                d[i] = nx[i] * x + ny[i] * y + c0[i];
                dmin = std::min(dmin, d[i]);
            }
            if (dmin <= -kSure)
                continue;
            int alpha = 256;
            if (dmin < kSure) {
                int inside = 0;
                for (const double oy : kOffsets)
                    for (const double ox : kOffsets) {
                        bool in = true;
                        for (int i = 0; i < 4 && in; ++i)
                            in = d[i] + nx[i] * ox + ny[i] * oy >= 0.0;
                        inside += in;
                    }
                if (inside == 0)
                    continue;
                alpha = inside * 16;
            }
            // Card coordinates of the pixel for its shading.
            const double w = hinv[6] * x + hinv[7] * y + hinv[8];
            const double u = std::clamp((hinv[0] * x + hinv[1] * y + hinv[2]) / w, -1.0, 1.0);
            const double v = std::clamp((hinv[3] * x + hinv[4] * y + hinv[5]) / w, -1.0, 1.0);
            const double light = paint.brightness + paint.gradientU * u + paint.gradientV * v;
            const int noise =
                static_cast<int>(noiseHash(static_cast<std::uint32_t>(x),
                                           static_cast<std::uint32_t>(y), paint.noiseSeed) %
                                 static_cast<std::uint32_t>(noiseSpan)) -
                noiseSpan / 2;
            for (int c = 0; c < 3; ++c) {
                const int card =
                    std::clamp(static_cast<int>(base[c] * light + 0.5) + noise, 0, 255);
                std::uint8_t& dst = p[offsets[c]];
                dst = static_cast<std::uint8_t>(dst + (((card - dst) * alpha) >> 8));
            }
        }
    }
    return true;
}

}  // namespace platform
