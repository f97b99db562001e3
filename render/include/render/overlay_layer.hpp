#pragma once
// OverlayLayer: something drawn over the mirrored video (card picture, hats and glasses, debug).

#include "vision/image.hpp"

namespace render {

/// What a layer needs to place itself over the video. Coordinates of the camera image (pixels,
/// origin top-left, x right, y down) map to normalised device coordinates by
///   ndc_x = imageToNdc[0] * x + imageToNdc[1],  ndc_y = imageToNdc[2] * y + imageToNdc[3].
/// The mirror flip is already inside that mapping (imageToNdc[0] < 0 when mirrored), so layers
/// place themselves in camera coordinates and come out mirrored with the video.
struct LayerContext {
    float imageToNdc[4] = {1.f, 0.f, 1.f, 0.f};
    vision::Size image;  ///< camera image size
    int viewportWidth = 0;
    int viewportHeight = 0;
    bool mirrored = true;
};

class OverlayLayer {
public:
    virtual ~OverlayLayer() = default;
    virtual const char* name() const noexcept = 0;
    /// Draws with GL state left as the renderer set it: blending on with standard
    /// (non-premultiplied) alpha (SRC_ALPHA, ONE_MINUS_SRC_ALPHA), depth and stencil tests off.
    /// Never throws.
    virtual void draw(const LayerContext& context) noexcept = 0;
};

}  // namespace render
