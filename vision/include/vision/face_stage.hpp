#pragma once
// FaceStage ("faces"): the FaceTracker (METHOD.md §3-4) run on the motion stage's reduced grey
// frame and its foreground mask. Faces are reported in camera-frame coordinates through
// FrameState::faces for the renderer, the HUD and the console.
#include "vision/face_tracker.hpp"
#include "vision/motion_stage.hpp"
#include "vision/scene_cut.hpp"
#include "vision/stage.hpp"

#include <array>

namespace vision {

class FaceStage final : public Stage {
public:
    /// Tracks faces on `motion`'s reduced grey image (the stage must run before this one and
    /// outlive it). `options.imageSize` is taken from it. Throws std::runtime_error on bad
    /// options (from FaceTracker).
    FaceStage(const MotionStage& motion, const HaarCascade& cascade, FaceTrackerOptions options);

    const char* name() const noexcept override { return "faces"; }
    /// Skips invalid frames and frames the motion stage could not use (faces then stay as they
    /// were; FrameState::faces is set either way). At a scene cut (SceneCut) the tracks are
    /// dropped first and the whole frame is scanned, as at start-up.
    void process(FrameState& state) noexcept override;
    /// Scene cuts seen since start-up.
    long cuts() const noexcept { return cuts_; }

    /// The faces of the last frame in camera-frame coordinates (points too), oldest first.
    std::span<const TrackedFace> faces() const noexcept { return {frameFaces_.data(), count_}; }
    /// Scene brightness around a face box of side `size` about `centre` (frame coordinates: a
    /// face of faces(), or a smoothed pose of one), relative to mid-grey (1 = grey 128): the mean
    /// of every second pixel of every second row of the box on the motion stage's grey image of
    /// the last frame. 1 when the box is outside the image.
    float brightnessAround(Point2f centre, float size) const noexcept;
    FaceTracker& tracker() noexcept { return tracker_; }
    const FaceTracker& tracker() const noexcept { return tracker_; }

private:
    static constexpr int kMaxFaces = 16;
    static constexpr int kMaxPoints = 64;
    const MotionStage& motion_;
    FaceTracker tracker_;
    std::array<TrackedFace, kMaxFaces> frameFaces_{};
    std::array<std::array<Point2f, kMaxPoints>, kMaxFaces> points_{};
    std::size_t count_ = 0;
    SceneCut sceneCut_;
    long cuts_ = 0;
};

}  // namespace vision
