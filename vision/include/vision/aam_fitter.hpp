#pragma once
// AamFitter: the real-time Active Appearance Model fit of §5 (dissertation 5.3.2, eq. 80): the
// inverse-compositional Gauss-Newton fit (Matthews & Baker) of the model's mean appearance to a
// grey image, on the appearance projected out of the span of its modes, with the global
// similarity q, brightness and contrast, and the CANDIDE-3 head as a soft constraint (scale, roll,
// pitch, yaw, translation, shape units sigma, animation units tau) weighted by K. It gives a face's
// 3D orientation and its six animation values.
//
// Built once from an AamModel at start-up: the steepest-descent images and the 2D Hessian are
// precomputed, and every buffer a fit needs is allocated then, sized from the model. fit() never
// allocates and never throws. One fitter serves every face in turn (it holds the scratch); each
// face keeps its own AamFaceState. Why each choice where 5.3 is silent: aam_fitter.cpp.

#include "vision/aam_model.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>

namespace vision {

/// The model sizes a fitter accepts (the buffers' and the Hessian's compile-time bounds).
inline constexpr int kAamAnimationUnits = 6;  ///< in the order of kTrackedAnimationUnits
inline constexpr int kAamShapeUnits = 10;     ///< in the order of kTrackedShapeUnits
inline constexpr int kAamMaxShapeModes = 24;
inline constexpr int kAamMaxVertices = 128;
/// The texture descriptor (appearanceParameters' second output): uniform local binary patterns,
/// this many bins per cell, in at most kAamMaxTextureGrid x kAamMaxTextureGrid cells.
inline constexpr int kAamLbpBins = 59;
inline constexpr int kAamMaxTextureGrid = 5;
inline constexpr int kAamMaxTextureBins = kAamMaxTextureGrid * kAamMaxTextureGrid * kAamLbpBins;

enum class AamSampling : std::uint8_t {
    Nearest,   ///< the nearest pixel (5.3.4: what the fit runs with)
    Bilinear,  ///< interpolated (the reference nearest is measured against)
};

struct AamFitterOptions {
    /// K of eq. 80: the 3D term's weight, per vertex and squared mean-frame pixel, against the
    /// 2D term's squared residual in units of the mean appearance's standard deviation.
    float constraintWeight = 0.5f;
    int maxIterations = 20;            ///< the cap on one fit's iterations (both phases)
    int maxSimilarityIterations = 10;  ///< a new face's first phase: q (and gain, bias) alone
    /// Converged when no vertex moved more than this (image pixels) and no angle more than
    /// convergedDegrees in the last iteration.
    float convergedPixels = 0.3f;
    float convergedDegrees = 0.3f;
    /// The same for a face fitted before (AamFaceState::fits > 0; fit() unless `fine`): it
    /// starts from the last frame's fit and the next frame goes on from where this one stops, so
    /// it need not settle as finely (docs/aam-evaluation.md: FGNet 8.5 -> 5.8 iterations a frame,
    /// about the same NME).
    float trackedConvergedPixels = 1.f;
    float trackedConvergedDegrees = 1.f;
    /// Verification: a fit whose projected-out appearance residual (rms, in units of the mean
    /// appearance's standard deviation) exceeds this is Rejected.
    float maxResidual = 0.8f;
    float maxAngleDegrees = 60.f;  ///< a fitted yaw or pitch beyond this is Rejected
    AamSampling sampling = AamSampling::Nearest;
    /// The shape units (the person's proportions) are fitted on a track's first fits and then
    /// frozen; the animation units keep following the face (5.3.3).
    int fitsBeforeShapeFreeze = 3;
    /// A new face starts from whichever of the frontal mean shape and the CANDIDE head turned
    /// this far to either side (degrees) its image matches best (0: always frontal).
    float startYawDegrees = 25.f;
    /// How appearanceParameters() samples the image: it runs only while a face's signature is
    /// collected (a few frames per track), so it can afford interpolation.
    AamSampling appearanceSampling = AamSampling::Bilinear;
    /// The texture descriptor's cells per side of the mean shape's frame (0: none; at most
    /// kAamMaxTextureGrid).
    int textureGrid = 4;
};

/// Where a face's mesh starts, from a face box (the tracker's position, scale and roll): the
/// centre and width of the mean shape's bounding box in the image, its roll clockwise on screen.
struct AamStart {
    Point2f centre{};
    float width = 0.f;
    float rollDegrees = 0.f;
};

/// The CANDIDE head of eq. 80: r = (scale, roll, pitch, yaw, translation), sigma and tau. Its
/// projection: image = translation + scale * Roll(roll) * Flip * Rx(pitch) * Ry(yaw) * g, where g
/// is the deformed CANDIDE shape in its model frame (x to the person's left, y up, z towards the
/// camera) and Flip turns y up into the image's y down.
struct AamHead {
    float scale = 0.f;  ///< image pixels per CANDIDE unit
    float roll = 0.f;   ///< radians, clockwise on screen
    float pitch = 0.f;  ///< radians, positive: the face turned down
    float yaw = 0.f;    ///< radians, positive: the face turned to its left (nose to image right)
    Point2f translation{};
    std::array<float, kAamShapeUnits> sigma{};
    std::array<float, kAamAnimationUnits> tau{};
};

/// What a fit knows of one face between frames. Plain data: a tracker keeps one per track.
struct AamFaceState {
    std::array<float, 4> q{};                  ///< the global similarity N (centred, orthonormal)
    std::array<float, kAamMaxShapeModes> p{};  ///< the 2D shape parameters
    float gain = 0.f, bias = 0.f;  ///< the image = gain * appearance + bias; gain 0: not yet set
    AamHead head{};
    bool headSet = false;  ///< head holds a fitted pose (else it is found from the 2D shape)
    int fits = 0;          ///< fits of this face so far (the shape units freeze after a few)
    bool shapeUnitsKept = false;  ///< head.sigma is the person's, kept over a restart: frozen
};

enum class AamFitOutcome : std::uint8_t {
    Converged,     ///< the parameter change fell under the thresholds
    IterationCap,  ///< stopped at maxIterations, verification passed
    Rejected,      ///< failed verification: residual, angle or shape implausible
    Diverged,      ///< left the image, collapsed, or produced no number
};

/// One face's fit. Only Converged and IterationCap are to be shown (ok()); otherwise the caller
/// falls back to the 2D pose and lets the tracker re-detect.
struct AamFitResult {
    AamFitOutcome outcome = AamFitOutcome::Diverged;
    float yawDegrees = 0.f, pitchDegrees = 0.f, rollDegrees = 0.f;
    Point2f translation{};  ///< where CANDIDE's origin projects, image pixels
    float scale = 0.f;      ///< image pixels per CANDIDE unit
    /// The six animation values, named by kTrackedAnimationUnits (candide_reduction.hpp).
    std::array<float, kAamAnimationUnits> animation{};
    float fitError = 0.f;  ///< projected-out appearance residual, rms, mean appearance's std = 1
    int iterations = 0;
    int vertexCount = 0;
    std::array<Point2f, kAamMaxVertices> vertices{};  ///< the fitted 2D shape, image pixels

    bool ok() const noexcept
    {
        return outcome == AamFitOutcome::Converged || outcome == AamFitOutcome::IterationCap;
    }
};

const char* aamFitOutcomeName(AamFitOutcome outcome) noexcept;

class AamFitter {
public:
    /// Precomputes the fit's tables from `model`. Throws std::invalid_argument (one line) for a
    /// model outside the bounds above or without the tracked units.
    explicit AamFitter(const AamModel& model, const AamFitterOptions& options = {});
    ~AamFitter();
    AamFitter(AamFitter&&) noexcept;
    AamFitter& operator=(AamFitter&&) noexcept;

    /// A new face: the mean shape placed on `start`, no pose yet.
    void start(AamFaceState& face, const AamStart& start) const noexcept;
    /// A known face started afresh on `start` (as start()), keeping its shape units once they
    /// froze: the person's proportions, fitted over its first frames, are not guessed again.
    void restart(AamFaceState& face, const AamStart& start) const noexcept;
    /// A tracked face moved from box `from` to box `to` (the tracker's similarity): the face's
    /// shape and head moved with it, as the next fit's start.
    void follow(AamFaceState& face, const AamStart& from, const AamStart& to) const noexcept;
    /// One fit of `face` on `grey` (Gray8), from its state; the state keeps the result. A new
    /// face (no fits yet) fits its similarity first, then everything (5.3.3). A face fitted
    /// before settles to options().trackedConvergedPixels unless `fine` (a fit whose result is
    /// kept beyond the frame, as a signature's).
    AamFitResult fit(ConstImageView grey, AamFaceState& face, bool fine = false) noexcept;

    /// The appearance parameters of `face` in its fitted state on `grey` (§6; dissertation 6.2):
    /// the image warped to the mean shape by the state's shape (options().appearanceSampling),
    /// less the mean appearance under the state's gain and bias and divided by the gain, as the
    /// fit measures its error, projected on the appearance modes (those the fit projects out:
    /// orthogonal to the mean appearance), each divided by its mode's standard deviation over the
    /// training faces. Writes min(out.size(), appearanceModeCount()) values and returns how many
    /// (0 for an image that is not Gray8 or a state without a gain). Integer warp and dot
    /// products (aam_kernels.hpp), the fitter's scratch: no allocation, no throw.
    int appearanceParameters(ConstImageView grey, const AamFaceState& face,
                             std::span<float> out) noexcept;
    /// The same, and from the same warp the face's texture descriptor into `texture` (beyond §6):
    /// each cell's (options().textureGrid squared, over the mean shape's frame) histogram of
    /// uniform local binary patterns (8 neighbours, 59 bins), as 255 * sqrt(the bin's share of
    /// its cell), so that Euclidean distance is the Hellinger distance. Writes textureSize()
    /// values when `texture` holds them (else none); integer but the final square roots.
    int appearanceParameters(ConstImageView grey, const AamFaceState& face, std::span<float> out,
                             std::span<std::uint8_t> texture) noexcept;
    /// How many values the texture descriptor has (cells * kAamLbpBins; 0: none).
    int textureSize() const noexcept;
    /// The appearance modes appearanceParameters() projects on.
    int appearanceModeCount() const noexcept;

    const AamFitterOptions& options() const noexcept;
    void setSampling(AamSampling sampling) noexcept;
    int vertexCount() const noexcept;

    struct Tables;
    struct Scratch;

private:
    void chooseStart(ConstImageView grey, AamFaceState& face) noexcept;
    double objective(AamFaceState& face, float error, bool similarityPhase) noexcept;
    void buildSystem(ConstImageView grey, AamFaceState& face, bool similarityPhase,
                     bool shapeFrozen) noexcept;
    bool shapeUnitsFrozen(const AamFaceState& face) const noexcept;

    std::unique_ptr<Tables> tables_;
    std::unique_ptr<Scratch> scratch_;
    AamFitterOptions options_;
};

}  // namespace vision
