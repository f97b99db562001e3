#pragma once
// `colorlab generate`: a recording of the illumination experiment with a known answer. Flat
// patches of eight construction-paper colours (as the dissertation's 8 samples, 3.2) lit by a white
// illuminant whose intensity ramps from maxGain down to minGain and back; a camera with a linear
// sensor (photon and read noise), clipping at full scale, and a 1/2.2 gamma, quantised to 8 bits.
// Under a pure intensity change every channel is scaled by the same factor (eq. 3) and the power
// law keeps it a common factor, so chromaticity and c1c2c3 are invariant up to noise and clipping;
// YIQ's I and Q scale with the light, HLS saturation changes past L = 0.5, and the hues of the
// near-grey patches (black, beige, brown) are unstable.

#include <cstdint>
#include <string>

namespace colorlab {

struct RampOptions {
    std::string outDir;
    int frames = 60;
    int width = 320;
    int height = 240;
    double minGain = 0.2;
    double maxGain = 1.6;
    double exposure = 0.8;      ///< sensor signal of a white patch at gain 1 (1 = full scale)
    double shotNoise = 2e-4;    ///< variance per unit signal (photon noise), linear units
    double readNoise = 1.5e-3;  ///< standard deviation, linear units
    double gamma = 2.2;
    std::uint32_t seed = 1;
};

/// Illuminant gain of frame i: a triangle maxGain -> minGain -> maxGain over the recording.
double rampGain(const RampOptions& options, int frame) noexcept;

/// Writes outDir/frame_NNNN.png, outDir/samples.txt (the patch centres, radius 3) and
/// outDir/illumination.csv (frame,gain). Throws std::runtime_error with one line on failure.
void generateRamp(const RampOptions& options);

}  // namespace colorlab
