#include "face_control.hpp"

#include "firmware/log.hpp"

namespace firmware {

namespace {

constexpr const char* kFaceStateNames[] = {"tentative", "shown", "missing"};

}  // namespace

FaceControl::FaceControl(vision::MotionStage& motion, vision::FaceStage& faces,
                         render::Renderer& renderer, bool debugHud)
    : motion_(motion), faces_(faces), debug_(std::make_unique<render::FaceDebugLayer>())
{
    debug_->setVisible(debugHud);
    renderer.addLayer(debug_.get());
}

void FaceControl::update(std::span<const vision::TrackedFace> faces) noexcept
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
}

}  // namespace firmware
