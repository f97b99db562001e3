#pragma once
// TrackedFaceFitter: the AAM fit (§5.3) run on every shown face of the tracker. Each track id has
// a fixed slot holding its AamFaceState: a new track (or one whose last fit failed) starts the
// fit from the tracker's box and roll (AamFitter::start, placed as AamBoxPlacement says); a
// track fitted well last frame follows the tracker's motion since then (AamFitter::follow) and
// fits from there; when that fit fails or its residual rose, it is fitted again from the box in
// the same frame (AamFitter::restart, the person's shape units kept) and the better fit kept. A
// fit the fitter rejects, or whose mesh left the tracker's box, is reported not ok (the face keeps
// the 2D pose) and the track starts afresh from its box next frame: a wrong fit is never carried
// on. Every buffer is allocated by the constructor; process() never allocates and never throws.

#include "vision/aam_fitter.hpp"
#include "vision/aam_model.hpp"
#include "vision/face_fit.hpp"
#include "vision/face_tracker.hpp"

#include <array>
#include <span>
#include <vector>

namespace vision {

/// Where a face's mesh starts in the tracker's face box (side s, rolled by the face's roll): the
/// mean shape's bounding box is widthOverBox * s wide and its centre lies downOverBox * s below
/// the box centre along the face's down axis. Measured on real faces (the Viola-Jones boxes of
/// the face tracker's detector and cascade, on the image halved as the motion stage halves it,
/// against the box of each annotation's CANDIDE fit), tools/aam/tests/aam_start_box_real_test.cpp:
///   IMM, 80 frontal images (types 1, 2):      width 0.714 (sd 0.030), down 0.174 (sd 0.019)
///   FGNet franck, every 10th of frames 0-999: width 0.755 (sd 0.022), down 0.177 (sd 0.014)
/// The defaults are the two sets' means. Sideways the mesh sits at the box centre (IMM +0.003,
/// FGNet -0.019 of the side to the right): no offset is kept.
struct AamBoxPlacement {
    float widthOverBox = 0.735f;
    float downOverBox = 0.175f;
};

struct TrackedFaceFitterOptions {
    AamFitterOptions fit{};
    AamBoxPlacement placement{};
    /// Beyond the fitter's own verification: the fitted mesh's box must stay within this fraction
    /// of the tracker's box side of where the tracker says it starts, and its width within these
    /// ratios of the start's width. The tracker's box is right about where the face is (it is
    /// verified every frame): a mesh that wandered off it fitted something else.
    float maxCentreShift = 0.3f;
    float minWidthRatio = 0.7f;
    float maxWidthRatio = 1.4f;
    /// Who a face is (FaceFit::signature) is the mean of a track's first this many ok fits taken
    /// after its shape units froze; then it is settled (§6).
    int signatureFits = 8;
    /// For the signature only: a fit the fitter rejected for its residual alone, up to this
    /// (the fitter's maxResidual is 0.8), still counts as an ok fit for a signature that is
    /// collecting (the track follows it and its shape units freeze as an ok fit's would). It is
    /// never shown (FaceFit::ok() stays false). 0: only ok fits. 1.0: chosen on a development
    /// model (docs/people-evaluation.md: more photographs with a signature, better rank-1).
    float signatureMaxResidual = 1.f;
    /// A followed fit whose residual rose by more than this over the track's last ok fit, or
    /// that failed, is fitted again from the tracker's box in the same frame and the better of
    /// the two kept: a mesh that slid (onto the hair, down the jaw) is caught before it fails,
    /// and a failed follow does not lose the frame. 0: never. Measured: docs/aam-evaluation.md.
    float restartResidualRise = 0.02f;
};

class TrackedFaceFitter {
public:
    static constexpr int kMaxFaces = 16;

    /// Builds the fitter's tables from `model` (not kept). Throws std::invalid_argument (one
    /// line) for a model the fitter cannot use.
    explicit TrackedFaceFitter(const AamModel& model, const TrackedFaceFitterOptions& options = {});

    /// Fits every shown face of `faces` (coordinates of `grey`, a Gray8 image) and forgets the
    /// tracks that are gone. fits() then has one entry per face of `faces` (at most kMaxFaces),
    /// in the same order; faces not shown are not fitted (FaceFit::fitted false).
    void process(ConstImageView grey, std::span<const TrackedFace> faces) noexcept;
    std::span<const FaceFit> fits() const noexcept { return {fits_.data(), count_}; }

    /// Where the fit of `face` starts (AamBoxPlacement applied to its box and roll).
    AamStart startFor(const TrackedFace& face) const noexcept;
    /// Forgets every track (a new camera, a rebuilt pipeline).
    void reset() noexcept;
    /// Keeps averaging track `faceId`'s signature over `fits` more ok fits than it has (enrolment
    /// collects a few seconds of them). False when no such track is being fitted.
    bool collectSignature(int faceId, int fits) noexcept;

    int vertexCount() const noexcept { return fitter_.vertexCount(); }
    /// The fitted mesh's triangles (indices into FaceFit::vertices), for drawing it.
    std::span<const std::array<int, 3>> triangles() const noexcept { return triangles_; }
    const TrackedFaceFitterOptions& options() const noexcept { return options_; }

private:
    struct Slot {
        int faceId = 0;  ///< 0: free
        bool seen = false;
        bool tracking = false;  ///< the last fit was ok: follow from it
        AamStart last{};        ///< the start box of the last frame (follow's `from`)
        float lastError = 0.f;  ///< the residual of the last ok fit
        AamFaceState state{};
        FaceSignature signature{};  ///< the running mean of the track's signatures
        int signatureTarget = 0;    ///< fits to average (0: options().signatureFits)
    };
    Slot* slotFor(int faceId) noexcept;
    /// The fits a slot's signature averages (its own target, else options().signatureFits).
    int signatureTargetOf(const Slot& slot) const noexcept;
    void fitFace(ConstImageView grey, const TrackedFace& face, Slot& slot, FaceFit& out) noexcept;
    /// Follows the track's last fit to `box` (or starts there), refitting from the box when the
    /// follow went wrong (options().restartResidualRise). `started`: the kept fit started afresh.
    AamFitResult fitTrack(ConstImageView grey, const TrackedFace& face, Slot& slot,
                          const AamStart& box, bool& started) noexcept;
    /// The mesh of `fit` stayed on the tracker's `box` of `face` (whether the fitter accepted it
    /// or not).
    bool plausible(const AamFitResult& fit, const AamStart& box,
                   const TrackedFace& face) const noexcept;
    void updateSignature(ConstImageView grey, Slot& slot, FaceFit& out, bool usable) noexcept;

    AamFitter fitter_;
    TrackedFaceFitterOptions options_;
    std::vector<std::array<int, 3>> triangles_;
    std::array<int, 4> eyeCorners_{};  ///< mesh indices of CANDIDE's eye corners 20, 23, 53, 56
    float meshWidthUnits_ = 1.f;       ///< CANDIDE units across the base mesh (x extent)
    std::array<Slot, kMaxFaces> slots_{};
    std::array<FaceFit, kMaxFaces> fits_{};
    std::size_t count_ = 0;
};

}  // namespace vision
