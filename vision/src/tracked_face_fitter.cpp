// TrackedFaceFitter (tracked_face_fitter.hpp): per-track AAM fits, started from the tracker's box
// and carried along by the tracker's motion while they hold (§5.3.3: a new face is fitted from the
// tracker's position, scale and roll; a tracked one from its last fit).
#include "vision/tracked_face_fitter.hpp"

#include "vision/candide_reduction.hpp"
#include "vision/face_slots.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

namespace {

/// The box of a fitted mesh: centre and width, as AamStart measures them.
AamStart meshBox(const AamFitResult& fit) noexcept
{
    float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
    for (int v = 0; v < fit.vertexCount; ++v) {
        const Point2f p = fit.vertices[static_cast<std::size_t>(v)];
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    return {{0.5f * (x0 + x1), 0.5f * (y0 + y1)}, x1 - x0, 0.f};
}

}  // namespace

TrackedFaceFitter::TrackedFaceFitter(const AamModel& model, const TrackedFaceFitterOptions& options)
    : fitter_(model, options.fit), options_(options), triangles_(model.mesh.triangles)
{
    const std::array<int, 4> corners{
        kCandideEyeOpenings[0].outerCorner, kCandideEyeOpenings[0].innerCorner,
        kCandideEyeOpenings[1].outerCorner, kCandideEyeOpenings[1].innerCorner};
    for (std::size_t i = 0; i < corners.size(); ++i)
        eyeCorners_[i] = model.mesh.indexOfCandideVertex(corners[i]);
    float x0 = 1e30f, x1 = -1e30f;
    for (const auto& v : model.mesh.vertices) {
        x0 = std::min(x0, v.x());
        x1 = std::max(x1, v.x());
    }
    meshWidthUnits_ = x1 > x0 ? x1 - x0 : 1.f;
}

AamStart TrackedFaceFitter::startFor(const TrackedFace& face) const noexcept
{
    const float roll = face.rollDegrees * kRadiansPerDegree;
    const float down = options_.placement.downOverBox * face.size;
    // The face's down axis on screen (y down, roll clockwise): (-sin, cos).
    AamStart s;
    s.centre = {face.centre.x - down * std::sin(roll), face.centre.y + down * std::cos(roll)};
    s.width = options_.placement.widthOverBox * face.size;
    s.rollDegrees = face.rollDegrees;
    return s;
}

void TrackedFaceFitter::reset() noexcept
{
    slots_.fill(Slot{});
    count_ = 0;
}

int TrackedFaceFitter::signatureTargetOf(const Slot& slot) const noexcept
{
    return slot.signatureTarget > 0 ? slot.signatureTarget : options_.signatureFits;
}

TrackedFaceFitter::Slot* TrackedFaceFitter::slotFor(int faceId) noexcept
{
    return vision::slotForFace(slots_, faceId);
}

void TrackedFaceFitter::process(ConstImageView grey, std::span<const TrackedFace> faces) noexcept
{
    for (Slot& s : slots_)
        s.seen = false;
    count_ = std::min(faces.size(), fits_.size());
    for (std::size_t i = 0; i < count_; ++i) {
        const TrackedFace& face = faces[i];
        FaceFit& out = fits_[i];
        out = FaceFit{};
        out.faceId = face.id;
        Slot* slot = slotFor(face.id);
        if (slot == nullptr)
            continue;
        slot->seen = true;
        if (!face.shown() || face.size <= 0.f) {
            slot->tracking = false;  // not shown: fitted afresh once it is
            continue;
        }
        fitFace(grey, face, *slot, out);
    }
    for (Slot& s : slots_)
        if (!s.seen)
            s.faceId = 0;  // the track is gone
}

void TrackedFaceFitter::fitFace(ConstImageView grey, const TrackedFace& face, Slot& slot,
                                FaceFit& out) noexcept
{
    const AamStart box = startFor(face);
    const AamFitResult fit = fitTrack(grey, face, slot, box, out.started);
    slot.last = box;

    out.fitted = true;
    out.outcome = fit.outcome;
    out.yawDegrees = fit.yawDegrees;
    out.pitchDegrees = fit.pitchDegrees;
    out.rollDegrees = fit.rollDegrees;
    out.translation = fit.translation;
    out.scale = fit.scale;
    out.animation = fit.animation;
    out.fitError = fit.fitError;
    out.iterations = fit.iterations;
    out.vertexCount = std::min(fit.vertexCount, kAamMaxVertices);
    std::copy_n(fit.vertices.begin(), out.vertexCount, out.vertices.begin());
    Point2f eyes{};
    int corners = 0;
    for (int v : eyeCorners_) {
        if (v < 0 || v >= out.vertexCount)
            continue;
        eyes.x += out.vertices[static_cast<std::size_t>(v)].x;
        eyes.y += out.vertices[static_cast<std::size_t>(v)].y;
        ++corners;
    }
    out.eyeMidpoint = corners > 0 ? Point2f{eyes.x / static_cast<float>(corners),
                                            eyes.y / static_cast<float>(corners)}
                                  : fit.translation;
    out.faceSize = fit.scale * meshWidthUnits_ / options_.placement.widthOverBox;

    out.plausible = plausible(fit, box, face);
    // A failed fit is not carried on: the next frame starts again from the tracker's box. A
    // collecting signature may take a fit rejected only for a residual slightly too large (never
    // shown): the track then follows it, and it counts towards the shape units' freeze.
    const int target = signatureTargetOf(slot);
    const float maxAngle = fitter_.options().maxAngleDegrees;
    const bool nearMiss =
        !out.ok() && out.plausible && slot.state.headSet &&
        fit.outcome == AamFitOutcome::Rejected && options_.signatureMaxResidual > 0.f &&
        fit.fitError <= options_.signatureMaxResidual && std::abs(fit.yawDegrees) <= maxAngle &&
        std::abs(fit.pitchDegrees) <= maxAngle && slot.signature.samples < target;
    if (nearMiss)
        ++slot.state.fits;
    slot.tracking = out.ok() || nearMiss;
    if (out.ok())
        slot.lastError = fit.fitError;
    updateSignature(grey, slot, out, out.ok() || nearMiss);
}

AamFitResult TrackedFaceFitter::fitTrack(ConstImageView grey, const TrackedFace& face, Slot& slot,
                                         const AamStart& box, bool& started) noexcept
{
    started = !slot.tracking;
    if (started)
        fitter_.start(slot.state, box);
    else
        fitter_.follow(slot.state, slot.last, box);
    // §6: a fit that goes into the track's signature settles finely; the others need not (the
    // next frame goes on from where they stop).
    const int target = signatureTargetOf(slot);
    const bool fine = slot.signature.samples < target;
    const AamFitResult followed = fitter_.fit(grey, slot.state, fine);
    const bool followedOk = followed.ok() && plausible(followed, box, face);
    // §5.3.3 carries a fit from frame to frame; a carried fit that slid keeps a residual just
    // under the fitter's limit for many frames before it fails (FGNet: onto the jaw line as the
    // mouth opens). A rise of the residual is the sign: the box's fit decides.
    const float rise = options_.restartResidualRise;
    if (started || rise <= 0.f ||
        (followedOk && followed.fitError <= slot.lastError + rise))
        return followed;
    AamFaceState fresh = slot.state;
    fitter_.restart(fresh, box);
    AamFitResult again = fitter_.fit(grey, fresh, fine);
    const int iterations = followed.iterations + again.iterations;
    const bool againOk = again.ok() && plausible(again, box, face);
    if (!againOk || (followedOk && followed.fitError <= again.fitError)) {
        AamFitResult kept = followed;
        kept.iterations = iterations;
        return kept;
    }
    slot.state = fresh;
    started = true;
    again.iterations = iterations;
    return again;
}

bool TrackedFaceFitter::plausible(const AamFitResult& fit, const AamStart& box,
                                  const TrackedFace& face) const noexcept
{
    // Where the mesh went against where the tracker says the face is.
    const AamStart mesh = meshBox(fit);
    const float dx = mesh.centre.x - box.centre.x, dy = mesh.centre.y - box.centre.y;
    const float shift = std::sqrt(dx * dx + dy * dy);
    // A turned head's mesh is narrower than the frontal start: compare the frontal width.
    const float width = fit.scale * meshWidthUnits_;
    return std::isfinite(shift) && std::isfinite(width) &&
           shift <= options_.maxCentreShift * face.size &&
           width >= options_.minWidthRatio * box.width &&
           width <= options_.maxWidthRatio * box.width;
}

bool TrackedFaceFitter::collectSignature(int faceId, int fits) noexcept
{
    for (Slot& s : slots_)
        if (s.faceId == faceId && faceId != 0) {
            const int target = signatureTargetOf(s);
            s.signatureTarget = std::max(target, s.signature.samples) + std::max(fits, 0);
            return true;
        }
    return false;
}

// §6: the signature is taken only from ok fits whose shape units are frozen (the person's
// proportions, not a first guess), averaged as a running mean so it never needs a buffer. The
// appearance parameters (a warp and one dot product per mode) are computed only for those fits,
// so a settled track costs nothing more per frame.
void TrackedFaceFitter::updateSignature(ConstImageView grey, Slot& slot, FaceFit& out,
                                        bool usable) noexcept
{
    const int target = signatureTargetOf(slot);
    FaceSignature& sig = slot.signature;
    if (usable && slot.state.fits > fitter_.options().fitsBeforeShapeFreeze &&
        sig.samples < target) {
        const float w = 1.f / static_cast<float>(sig.samples + 1);
        for (int i = 0; i < kAamShapeUnits; ++i)
            sig.shapeUnits[i] += w * (slot.state.head.sigma[i] - sig.shapeUnits[i]);
        std::array<float, kFaceSignatureMaxAppearance> appearance{};
        std::array<std::uint8_t, kFaceSignatureMaxTexture> texture{};
        const int count = fitter_.appearanceParameters(grey, slot.state, appearance, texture);
        const int textureCount = std::min(fitter_.textureSize(), kFaceSignatureMaxTexture);
        if (sig.samples == 0 || textureCount != sig.textureCount) {
            sig.textureCount = textureCount;
            std::copy_n(texture.begin(), textureCount, sig.texture.begin());
        } else {
            // The running mean in whole units (each step rounded to the nearest).
            for (int i = 0; i < textureCount; ++i) {
                auto& v = sig.texture[static_cast<std::size_t>(i)];
                v = static_cast<std::uint8_t>(std::clamp(
                    static_cast<int>(std::lround(
                        static_cast<float>(v) +
                        w * static_cast<float>(texture[static_cast<std::size_t>(i)] - v))),
                    0, 255));
            }
        }
        if (sig.samples == 0 || count != sig.appearanceCount) {
            // The first sample (or, never with one model, a count that changed): start afresh.
            sig.appearanceCount = count;
            for (int i = 0; i < count; ++i)
                sig.appearance[static_cast<std::size_t>(i)] =
                    appearance[static_cast<std::size_t>(i)];
        } else {
            for (int i = 0; i < count; ++i)
                sig.appearance[static_cast<std::size_t>(i)] +=
                    w * (appearance[static_cast<std::size_t>(i)] -
                         sig.appearance[static_cast<std::size_t>(i)]);
        }
        ++sig.samples;
    }
    out.signature = sig;
    out.signatureSettled = sig.samples >= target;
}

}  // namespace vision
