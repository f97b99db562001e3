#pragma once
// FaceFit: what the AAM fit (§5.3) found for one tracked face in one frame, beside its
// TrackedFace (FrameState::fits, the same order as FrameState::faces, matched by id): the 3D
// pose, the six animation values, how well the model fits, and the fitted 2D mesh. Plain data,
// fixed size: the frame state holds an array of them, allocated at start-up.

#include "vision/aam_fitter.hpp"
#include "vision/face_signature.hpp"
#include "vision/geometry.hpp"

#include <array>
#include <span>
#include <string_view>

namespace vision {

/// The animation values' short names, in the order of AamFitResult::animation (that of
/// kTrackedAnimationUnits: Jaw drop, Lip stretcher, Brow lowerer, Outer brow raiser, Upper lip
/// raiser, Lip corner depressor).
inline constexpr std::array<std::string_view, kAamAnimationUnits> kFaceFitAnimationNames{
    "jaw_drop",          "lip_stretcher",    "brow_lowerer",
    "outer_brow_raiser", "upper_lip_raiser", "lip_corner_depressor"};

struct FaceFit {
    int faceId = 0;        ///< the TrackedFace::id it belongs to
    bool fitted = false;   ///< a fit ran this frame (only shown faces are fitted)
    bool started = false;  ///< the fit started from the tracker's box (new face or after a failure)
    /// The fit's own verdict (converged, iteration cap, rejected, diverged).
    AamFitOutcome outcome = AamFitOutcome::Diverged;
    /// False when the fitted mesh left the tracker's box (moved or grew beyond the bounds of
    /// TrackedFaceFitterOptions): a fit can converge on the wrong thing.
    bool plausible = false;
    float yawDegrees = 0.f, pitchDegrees = 0.f, rollDegrees = 0.f;  ///< AamHead's conventions
    Point2f translation{};  ///< where CANDIDE's origin projects, image pixels
    float scale = 0.f;      ///< image pixels per CANDIDE unit
    std::array<float, kAamAnimationUnits> animation{};  ///< named by kFaceFitAnimationNames
    float fitError = 0.f;                               ///< AamFitResult::fitError
    int iterations = 0;
    /// The midpoint of the fitted eye corners (image pixels) and the tracker box side the fitted
    /// mesh corresponds to (its width over the start placement's width ratio): what
    /// headPoseFromFit places the head by, as headPoseFromFace does from the box.
    Point2f eyeMidpoint{};
    float faceSize = 0.f;
    int vertexCount = 0;
    std::array<Point2f, kAamMaxVertices> vertices{};  ///< the fitted mesh, image pixels
    /// Who the face is (§6): the mean over the track's first ok fits (TrackedFaceFitter);
    /// signature.samples counts them. Settled once it has the fits recognition waits for: from
    /// then on it no longer changes (unless more are asked for, as enrolment does).
    FaceSignature signature{};
    bool signatureSettled = false;

    /// Shown: the pose may place overlays; otherwise the face keeps the 2D pose.
    bool ok() const noexcept
    {
        return fitted && plausible &&
               (outcome == AamFitOutcome::Converged || outcome == AamFitOutcome::IterationCap);
    }
    /// One word for logs and the console: "ok", "not-fitted", "implausible" or the outcome.
    const char* status() const noexcept
    {
        if (!fitted)
            return "not-fitted";
        if (outcome != AamFitOutcome::Converged && outcome != AamFitOutcome::IterationCap)
            return aamFitOutcomeName(outcome);
        return plausible ? "ok" : "implausible";
    }
};

/// The fit of face `faceId` in `fits`, or null.
inline const FaceFit* fitFor(std::span<const FaceFit> fits, int faceId) noexcept
{
    for (const FaceFit& f : fits)
        if (f.faceId == faceId)
            return &f;
    return nullptr;
}

}  // namespace vision
