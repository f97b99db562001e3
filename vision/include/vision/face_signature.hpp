#pragma once
// FaceSignature: who a fitted face is, as the AAM fit sees it (§6; dissertation 6.2). Two parts,
// as the dissertation suggests: the CANDIDE shape units the fit freezes for a track (eye height
// and separation, mouth width...: constant for one person across lighting, glasses and pose), and
// the appearance parameters (the face's pixels warped to the mean shape, gain and bias removed,
// projected on the model's appearance modes: already free of pose, shape and expression). A
// track's signature is the mean over its first ok fits (TrackedFaceFitter). Plain data, fixed
// size: it is copied per face per frame and written to a person's file as numbers.

#include "vision/aam_fitter.hpp"

#include <array>

namespace vision {

/// The most appearance parameters a signature keeps (a model's first modes beyond are dropped).
inline constexpr int kFaceSignatureMaxAppearance = 64;

struct FaceSignature {
    std::array<float, kAamShapeUnits> shapeUnits{};  ///< sigma of the fitted head, CANDIDE units
    /// lambda_i of the appearance modes, each in units of its mode's standard deviation.
    std::array<float, kFaceSignatureMaxAppearance> appearance{};
    int appearanceCount = 0;  ///< how many of `appearance` the model filled
    int samples = 0;          ///< ok fits averaged into it; 0: nothing known yet
};

}  // namespace vision
