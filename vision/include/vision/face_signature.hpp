#pragma once
// FaceSignature: who a fitted face is, as the AAM fit sees it (§6; dissertation 6.2). Two parts,
// as the dissertation suggests: the CANDIDE shape units the fit freezes for a track (eye height
// and separation, mouth width...: constant for one person across lighting, glasses and pose), and
// the appearance parameters (the face's pixels warped to the mean shape, gain and bias removed,
// projected on the model's appearance modes: already free of pose, shape and expression); and,
// beyond the method, a texture descriptor of the same warped face (local binary patterns). A
// track's signature is the mean over its first ok fits (TrackedFaceFitter). Plain data, fixed
// size: it is copied per face per frame and written to a person's file as numbers.

#include "vision/aam_fitter.hpp"

#include <array>
#include <cstdint>

namespace vision {

/// The most appearance parameters a signature keeps (a model's first modes beyond are dropped).
inline constexpr int kFaceSignatureMaxAppearance = 64;
/// The most texture values a signature keeps (AamFitter's descriptor at its largest grid).
inline constexpr int kFaceSignatureMaxTexture = kAamMaxTextureBins;

struct FaceSignature {
    std::array<float, kAamShapeUnits> shapeUnits{};  ///< sigma of the fitted head, CANDIDE units
    /// lambda_i of the appearance modes, each in units of its mode's standard deviation.
    std::array<float, kFaceSignatureMaxAppearance> appearance{};
    int appearanceCount = 0;  ///< how many of `appearance` the model filled
    /// The texture descriptor (beyond §6): uniform local binary patterns per cell of the face
    /// warped to the mean shape, 255 * sqrt(the pattern's share of its cell) (AamFitter).
    std::array<std::uint8_t, kFaceSignatureMaxTexture> texture{};
    int textureCount = 0;  ///< how many of `texture` the fitter filled (0: none)
    int samples = 0;       ///< ok fits averaged into it; 0: nothing known yet
};

}  // namespace vision
