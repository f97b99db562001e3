#include "vision/card_training_check.hpp"

#include "vision/card_color_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vision {

namespace {

/// Mean of (R + G + B) / 3 over `r` (already clipped); 0 for a format without RGB bytes.
float meanBrightness(const ConstImageView& rgb, Rect r) noexcept
{
    const int bpp = rgbLayout(rgb.format).bytesPerPixel;
    if (bpp == 0 || r.width <= 0 || r.height <= 0)
        return 0.f;
    const RgbLayout layout = rgbLayout(rgb.format);
    std::uint64_t sum = 0;
    for (int y = r.y; y < r.y + r.height; ++y) {
        const std::uint8_t* p = rgb.row(y) + static_cast<std::ptrdiff_t>(r.x) * bpp;
        for (int x = 0; x < r.width; ++x, p += bpp)
            sum += static_cast<unsigned>(p[layout.r]) + p[layout.g] + p[layout.b];
    }
    return static_cast<float>(static_cast<double>(sum) /
                              (3.0 * static_cast<double>(r.width) * r.height));
}

}  // namespace

CardTrainingCheck checkCardTrainingRegion(const ConstImageView& rgb,
                                          const ChromaticityPlanes& chroma, Rect region,
                                          const CardTrainingLimits& limits) noexcept
{
    CardTrainingCheck check;
    CardColorModel spread;  // §2 step 1's statistics without the sigma floor: the true spread
    if (rgb.size() != chroma.r.size() || !trainColorModel(chroma, region, 0.f, spread))
        return check;
    for (int c = 0; c < 3; ++c) {
        check.sigma = std::max(check.sigma, spread.sigma[c]);
        check.saturation = std::max(check.saturation, std::fabs(spread.mean[c] - 255.f / 3.f));
    }
    check.brightness = meanBrightness(rgb, clipped(region, rgb.width, rgb.height));
    check.uniform = check.sigma <= limits.maxSigma;
    check.saturated = check.saturation >= limits.minSaturation;
    check.lit = check.brightness >= limits.minBrightness;
    return check;
}

}  // namespace vision
