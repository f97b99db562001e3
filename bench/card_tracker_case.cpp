#include "card_tracker_case.hpp"

#include "bench_setup.hpp"
#include "platform/card_scene_source.hpp"
#include "platform/frame_source.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace bench {

namespace {

/// A camera that sees the same photograph every frame.
class StillSource final : public platform::FrameSource {
public:
    explicit StillSource(const cv::Mat& bgr) : bgr_(bgr) {}
    const char* description() const noexcept override { return "still photograph"; }
    vision::Size size() const noexcept override { return {bgr_.cols, bgr_.rows}; }
    vision::PixelFormat format() const noexcept override { return vision::PixelFormat::BGR24; }
    platform::SourceStatus next(vision::Frame& frame) noexcept override
    {
        frame.image = bgrView(bgr_);
        frame.sequence = sequence_++;
        frame.timestampNs = static_cast<std::int64_t>(frame.sequence) * 33'333'333;
        return platform::SourceStatus::Ok;
    }

private:
    const cv::Mat& bgr_;
    std::uint64_t sequence_ = 0;
};

/// The central half (in each direction) of the quad's bounding box: inside the card.
vision::Rect centralRegion(const vision::Quad& q)
{
    const auto [x0, y0, x1, y1] = vision::extentOf(q);
    const float w = x1 - x0, h = y1 - y0;
    return {static_cast<int>(x0 + w / 4), static_cast<int>(y0 + h / 4), static_cast<int>(w / 2),
            static_cast<int>(h / 2)};
}

}  // namespace

CardTrackerCase::CardTrackerCase(const cv::Mat& bgr, int frames)
    : r_(bgr.cols, bgr.rows, vision::PixelFormat::Gray8),
      g_(bgr.cols, bgr.rows, vision::PixelFormat::Gray8),
      b_(bgr.cols, bgr.rows, vision::PixelFormat::Gray8)
{
    platform::CardSceneSource scene(std::make_unique<StillSource>(bgr));
    for (int i = 0; i < frames; ++i) {
        vision::Frame frame;
        if (scene.next(frame) != platform::SourceStatus::Ok)
            throw std::runtime_error("mirror-bench: the card scene stopped delivering frames");
        vision::ImageBuffer copy(frame.image.width, frame.image.height, frame.image.format);
        auto dst = copy.view();
        for (int y = 0; y < dst.height; ++y)
            std::memcpy(dst.row(y), frame.image.row(y), static_cast<std::size_t>(dst.width) * 3);
        frames_.push_back(std::move(copy));
        truth_.push_back(scene.corners());
    }
    trainRegion_ = centralRegion(truth_.front());
    tracker_ = std::make_unique<vision::CardTracker>(vision::Size{bgr.cols, bgr.rows});
    restart();
}

vision::ChromaticityPlanes CardTrackerCase::planes()
{
    return {r_.view(), g_.view(), b_.view()};
}

void CardTrackerCase::restart()
{
    const vision::ConstImageView first = frames_.front().view();
    vision::convertChromaticity(table_, first, planes());
    tracker_->train(first, planes(), trainRegion_);
    next_ = 1;
    tracked_ = 0;
    errorSum_ = 0.0;
}

bool CardTrackerCase::step()
{
    if (next_ >= frames())
        return false;
    const vision::ConstImageView frame = frames_[static_cast<std::size_t>(next_)].view();
    vision::convertChromaticity(table_, frame, planes());
    const vision::CardObservation& seen = tracker_->process(frame, planes());
    if (seen.state == vision::CardState::Tracking && seen.hasQuad) {
        ++tracked_;
        const vision::Quad& truth = truth_[static_cast<std::size_t>(next_)];
        for (int c = 0; c < 4; ++c)
            errorSum_ += std::hypot(seen.quad[c].x - truth[c].x, seen.quad[c].y - truth[c].y);
    }
    ++next_;
    return true;
}

}  // namespace bench
