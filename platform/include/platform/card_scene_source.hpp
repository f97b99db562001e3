#pragma once
// CardSceneSource: composites a synthetic coloured card moving over another source's frames.

#include "platform/frame_source.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>
#include <string>

namespace platform {

/// Appearance and size of the synthetic card.
struct CardSceneOptions {
    std::uint8_t red = 40;  ///< card colour (RGB, whatever the frame's byte order)
    std::uint8_t green = 172;
    std::uint8_t blue = 76;
    double heightFraction = 0.30;  ///< the unrotated card's height / the frame's (0.25..0.35)
    bool portrait = false;         ///< A5 upright (long side vertical) instead of landscape
    double shading = 0.08;         ///< brightness varies within 1 +- shading (gradient and tilt)
    int noise = 4;                 ///< per-pixel noise, +- grey levels, deterministic
    int introFrames = 0;           ///< frames held up for training first, then as many easing out
    /// Where the card wanders after the intro: the centre of its path as fractions of the frame
    /// (0.5, 0.5 with the whole view to swing in; elsewhere it swings as far as it still fits).
    double pathCentreX = 0.5;
    double pathCentreY = 0.5;

    /// Green construction paper (the default).
    static constexpr CardSceneOptions greenCard() noexcept { return {}; }
    /// Magenta construction paper.
    static constexpr CardSceneOptions magentaCard() noexcept
    {
        CardSceneOptions o;
        o.red = 204;
        o.green = 42;
        o.blue = 140;
        return o;
    }
};

/// Decorator for the demo scene: the inner source's frames with a solid-coloured card drawn over
/// them, and the card's true corners for checking the card tracker.
///
/// The card is an A5-proportioned rectangle seen in perspective: it moves along a smooth Lissajous
/// path and tilts and turns gently in 3D, a pure function of the frame's sequence number (scene
/// time 1/30 s per frame). Its size and path are chosen at construction so the whole card always
/// stays inside the frame. It is drawn by drawCardQuad() (card_raster.hpp): anti-aliased edges,
/// slight brightness shading and mild noise so it is not perfectly flat, no highlighted border.
///
/// Frames are copied into a buffer of this source (same size and format as the inner one: RGB24,
/// BGR24 or XRGB8888), so the inner source's frame is never modified. EndOfStream and Lost of the
/// inner source are passed through. next() never allocates.
class CardSceneSource final : public FrameSource {
public:
    /// Throws std::runtime_error when `inner` is null, too small (< 32 pixels a side) or delivers a
    /// format other than RGB24, BGR24, XRGB8888.
    explicit CardSceneSource(std::unique_ptr<FrameSource> inner,
                             const CardSceneOptions& options = CardSceneOptions{});

    const char* description() const noexcept override { return description_.c_str(); }
    vision::Size size() const noexcept override { return size_; }
    vision::PixelFormat format() const noexcept override { return format_; }
    SourceStatus next(vision::Frame& frame) noexcept override;
    std::int64_t lastWaitNs() const noexcept override { return inner_->lastWaitNs(); }
    const char* lastError() const noexcept override;

    /// Corners of the card in the last delivered frame (of sequence 0 before the first), clockwise
    /// on screen from the card's top-left corner: top-left, top-right, bottom-right, bottom-left.
    vision::Quad corners() const noexcept { return corners_; }
    /// Corners of the card in the frame with this sequence number.
    vision::Quad cornersFor(std::uint64_t sequence) const noexcept;
    /// Draws the card of frame `sequence` into `image` (this source's size and format); false when
    /// the image does not fit. next() uses it on its copy of the inner frame.
    bool drawCard(std::uint64_t sequence, vision::ImageView image) const noexcept;

    const CardSceneOptions& options() const noexcept { return options_; }
    FrameSource& inner() noexcept { return *inner_; }

private:
    struct Pose;
    Pose poseFor(std::uint64_t sequence) const noexcept;

    std::unique_ptr<FrameSource> inner_;
    CardSceneOptions options_;
    vision::Size size_;
    vision::PixelFormat format_;
    vision::ImageBuffer buffer_;
    std::string description_;
    vision::Quad corners_{};
    char lastError_[160] = {};

    // Geometry fixed at construction (pixels).
    double halfWidth_ = 0.0;   ///< half extent of the card along its own x axis
    double halfHeight_ = 0.0;  ///< along its own y axis
    double focal_ = 0.0;       ///< focal length of the virtual camera
    double depth_ = 0.0;       ///< distance of the card centre from the camera
    double centreX_ = 0.0;     ///< the centre of the card's path, in pixels
    double centreY_ = 0.0;
    double pathX_ = 0.0;       ///< amplitude of the card centre's path around it
    double pathY_ = 0.0;
};

}  // namespace platform
