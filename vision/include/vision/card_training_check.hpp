#pragma once
// Whether a region is fit to train the card's colour on (§2 step 1 assumes the card fills it).
// The appliance trains on the centre of the frame when asked; with no card held there it would
// learn the wall, a face or a mixture and never find a card again. A region qualifies when it is
// one colour (small chromaticity spread), a saturated one (chromaticity far from grey) and lit
// (dark pixels have no reliable chromaticity).

#include "vision/chromaticity.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

namespace vision {

struct CardTrainingLimits {
    float maxSigma = 12.f;       ///< largest chromaticity standard deviation (0..255) allowed
    float minSaturation = 30.f;  ///< least distance of the mean chromaticity from grey (85)
    float minBrightness = 40.f;  ///< least mean of (R + G + B) / 3 (0..255)
};

/// The region's measurements and the verdict.
struct CardTrainingCheck {
    float sigma = 0.f;       ///< the largest of the three chromaticity standard deviations
    float saturation = 0.f;  ///< the largest |mean chromaticity - 255/3| of the three channels
    float brightness = 0.f;  ///< mean of (R + G + B) / 3 over the region
    bool uniform = false;
    bool saturated = false;
    bool lit = false;
    bool ok() const noexcept { return uniform && saturated && lit; }
};

/// Measures `region` (clipped to the frame) of `rgb` (RGB24, BGR24 or XRGB8888) and its
/// chromaticity planes against `limits`. An empty region or missing planes fail every test.
CardTrainingCheck checkCardTrainingRegion(const ConstImageView& rgb,
                                          const ChromaticityPlanes& chroma, Rect region,
                                          const CardTrainingLimits& limits = {}) noexcept;

}  // namespace vision
