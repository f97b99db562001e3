#include "vision/face_stage.hpp"

#include <algorithm>

namespace vision {

namespace {

FaceTrackerOptions withImageSize(FaceTrackerOptions options, const MotionStage& motion)
{
    const ConstImageView gray = motion.gray();
    options.imageSize = {gray.width, gray.height};
    return options;
}

}  // namespace

FaceStage::FaceStage(const MotionStage& motion, const HaarCascade& cascade,
                     FaceTrackerOptions options)
    : motion_(motion), tracker_(cascade, withImageSize(options, motion))
{
}

void FaceStage::process(FrameState& state) noexcept
{
    if (state.valid && motion_.ok()) {
        const ConstImageView gray = motion_.gray();
        if (sceneCut_.update(motion_.foregroundPixels(), gray.width * gray.height)) {
            tracker_.resetAfterCut();  // the tracks are of a picture that is gone
            ++cuts_;
        }
        tracker_.process(gray, motion_.mask(), &motion_.maskIntegral());
    } else {
        sceneCut_.reset();
    }
    // Working image -> frame coordinates: the motion stage's grey image is the frame shrunk by
    // an integer factor.
    const float k = static_cast<float>(motion_.downscale());
    const std::span<const TrackedFace> faces = tracker_.faces();
    count_ = std::min(faces.size(), frameFaces_.size());
    for (std::size_t i = 0; i < count_; ++i) {
        TrackedFace f = faces[i];
        f.centre = motion_.toFrame(f.centre);
        f.size *= k;
        const int n = std::min(f.pointCount, kMaxPoints);
        for (int p = 0; p < n; ++p)
            points_[i][static_cast<std::size_t>(p)] = motion_.toFrame(f.points[p]);
        f.points = points_[i].data();
        f.pointCount = n;
        frameFaces_[i] = f;
    }
    state.faces = this->faces();
}

float FaceStage::brightnessAround(Point2f centre, float size) const noexcept
{
    const ConstImageView gray = motion_.gray();
    const float k = static_cast<float>(motion_.downscale());
    const int half = std::max(1, static_cast<int>(size / k * 0.5f));
    const int cx = static_cast<int>(centre.x / k), cy = static_cast<int>(centre.y / k);
    long sum = 0, count = 0;
    for (int y = std::max(0, cy - half); y < std::min(gray.height, cy + half); y += 2)
        for (int x = std::max(0, cx - half); x < std::min(gray.width, cx + half); x += 2) {
            sum += gray.row(y)[x];
            ++count;
        }
    const float mean = count > 0 ? static_cast<float>(sum) / static_cast<float>(count) : 128.f;
    return mean / 128.f;
}

}  // namespace vision
