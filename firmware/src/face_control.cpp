#include "face_control.hpp"

#include "firmware/log.hpp"

namespace firmware {

namespace {

constexpr const char* kFaceStateNames[] = {"tentative", "shown", "missing"};

}  // namespace

FaceControl::FaceControl(vision::MotionStage& motion, vision::FaceStage& faces,
                         vision::AamStage* aam, render::Renderer& renderer, bool debugHud)
    : motion_(motion), faces_(faces), aam_(aam), debug_(std::make_unique<render::FaceDebugLayer>())
{
    debug_->setVisible(debugHud);
    if (aam_ != nullptr)
        debug_->setMeshTriangles(aam_->fitter().triangles());
    renderer.addLayer(debug_.get());
}

void FaceControl::update(std::span<const vision::TrackedFace> faces,
                         std::span<const vision::FaceFit> fits) noexcept
{
    if (faces_.cuts() != cuts_) {
        cuts_ = faces_.cuts();
        MIRROR_LOG_INFO(
            "faces: the whole view changed at once (scene cut %ld): tracks dropped, "
            "the frame scanned",
            cuts_);
    }
    int shown = 0;
    for (const vision::TrackedFace& f : faces)
        shown += f.shown();
    if (shown != shown_)
        MIRROR_LOG_INFO("faces: %d shown (was %d)", shown, shown_);
    shown_ = shown;
    debug_->update(faces);
    debug_->updateFits(fits);
}

void FaceControl::format(Reply& reply) const noexcept
{
    const std::span<const vision::TrackedFace> faces = faces_.faces();
    int shown = 0;
    for (const vision::TrackedFace& f : faces)
        shown += f.shown();
    reply.printf("faces: %d shown, %d tracked, motion %d px\n", shown,
                 static_cast<int>(faces.size()), motion_.foregroundPixels());
    for (const vision::TrackedFace& f : faces)
        reply.printf(
            "face %d: %s centre (%.1f, %.1f) size %.1f roll %.1f deg confidence %.2f "
            "age %d points %d\n",
            f.id, kFaceStateNames[static_cast<int>(f.state)], static_cast<double>(f.centre.x),
            static_cast<double>(f.centre.y), static_cast<double>(f.size),
            static_cast<double>(f.rollDegrees), static_cast<double>(f.confidence), f.age,
            f.pointCount);
    if (aam_ == nullptr)
        return;
    // §5.3: the fit of each face, or why its overlays keep the 2D pose.
    const std::span<const vision::FaceFit> fits = aam_->fits();
    for (const vision::TrackedFace& f : faces) {
        const vision::FaceFit* fit = vision::fitFor(fits, f.id);
        if (fit == nullptr || !fit->fitted) {
            reply.printf("face %d: aam not fitted (2D pose)\n", f.id);
            continue;
        }
        reply.printf("face %d: aam %s%s yaw %.1f pitch %.1f roll %.1f deg error %.2f "
                     "iterations %d\n",
                     f.id, fit->status(), fit->ok() ? "" : " (2D pose)",
                     static_cast<double>(fit->yawDegrees), static_cast<double>(fit->pitchDegrees),
                     static_cast<double>(fit->rollDegrees), static_cast<double>(fit->fitError),
                     fit->iterations);
        reply.printf("face %d: aam", f.id);
        for (std::size_t u = 0; u < vision::kFaceFitAnimationNames.size(); ++u)
            reply.printf(" %.*s %.2f", static_cast<int>(vision::kFaceFitAnimationNames[u].size()),
                         vision::kFaceFitAnimationNames[u].data(),
                         static_cast<double>(fit->animation[u]));
        reply.printf("\n");
    }
}

}  // namespace firmware
