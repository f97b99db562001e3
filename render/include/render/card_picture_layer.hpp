#pragma once
// CardPictureLayer: the picture on the colour card (§2, dissertation 4.2.5), drawn over the
// mirrored video.

#include "render/overlay_layer.hpp"
#include "vision/card_tracker.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <memory>

namespace render {

/// \class CardPictureLayer
/// Maps a picture onto the card the tracker follows, with perspective-correct texturing, and
/// shows it only on card-coloured pixels so that a hand in front of the card hides the picture.
///
/// Per frame the firmware calls update() with the tracker's observation, then Renderer::draw(),
/// which calls draw(). Only a card in state Tracking with a quad is drawn; otherwise nothing.
///
/// How it is drawn: the homography H from the unit square to the quad (picture corners TL, TR, BR,
/// BL onto quad corners 0..3) is computed on the CPU; its inverse goes to the fragment shader as a
/// mat3, which maps every fragment's camera-pixel position back to picture coordinates. The
/// geometry is the quad's screen-aligned bounding box in camera coordinates, placed through
/// LayerContext::imageToNdc, so the picture is mirrored with the video. Because the lookup runs
/// per fragment in camera coordinates, the mapping is exact under perspective and unaffected by
/// the mirror reversing the quad's on-screen winding. Like a print on a real card seen in a real
/// mirror, the picture appears left-right reversed on screen.
///
/// Occlusion: where the dissertation (4.2.5) writes depth from the object mask, this layer samples
/// the mask itself (uploaded as a luminance texture, linearly filtered) and uses it as the
/// picture's alpha: mask 0 (not card colour: a hand, the background) lets the video show, and the
/// filtered edge between 0 and 255 blends instead of stepping, so the border is not jagged. One
/// pass, no depth or stencil buffer needed (the display may have none). The quad's own edges are
/// anti-aliased too: the shader ramps alpha over the half screen pixel either side of them.
///
/// Without a picture (asset missing or unreadable) the layer draws the quad's outline instead,
/// so the tracker can still be seen working.
///
/// Coordinates: vision's geometry puts pixel centres at integers; LayerContext's mapping puts
/// the image's edges at 0 and width, so a quad corner (x, y) is drawn at (x + 0.5, y + 0.5).
///
/// Construction needs the GL context current and allocates; update() and draw() never allocate
/// and never throw (GL errors are collected by the renderer after the layers).
class CardPictureLayer : public OverlayLayer {
public:
    /// `picture` (RGB24) is copied into a texture now; an empty view selects outline mode.
    /// `cameraSize` is the size of the frames the tracker sees (and of its mask).
    /// Throws std::runtime_error with one line when the picture is not RGB24 or too large for a
    /// texture, or GL objects cannot be made.
    CardPictureLayer(const vision::ConstImageView& picture, vision::Size cameraSize);
    ~CardPictureLayer() override;
    CardPictureLayer(const CardPictureLayer&) = delete;
    CardPictureLayer& operator=(const CardPictureLayer&) = delete;

    const char* name() const noexcept override { return "card picture"; }

    /// Takes this frame's card (null: none). Copies the quad and the mask, so `card` need not
    /// outlive the call. A mask that is empty or not Gray8 at the camera size is ignored (the
    /// picture then covers the whole quad) and lastError() says so. Does no GL work.
    void update(const vision::CardObservation* card) noexcept;
    void draw(const LayerContext& context) noexcept override;

    /// True when constructed without a picture: draw() outlines the quad.
    bool outlineMode() const noexcept { return outline_; }
    /// True when the last update() left something to draw.
    bool visible() const noexcept { return visible_; }
    /// Why the last update() could not use the mask; "" when it could.
    const char* lastError() const noexcept { return lastError_; }

    /// Inverse of the homography taking the unit square's corners (0,0), (1,0), (1,1), (0,1) to
    /// the quad's corners 0..3: row-major 3x3, maps homogeneous image points to homogeneous
    /// (u, v, w). False for a degenerate quad (three corners on a line or a fold).
    static bool unitSquareToQuadInverse(const vision::Quad& quad, float inverse[9]) noexcept;

private:
    struct Gl;
    std::unique_ptr<Gl> gl_;
    vision::Size camera_;
    bool outline_ = false;
    bool visible_ = false;
    bool maskDirty_ = false;
    vision::Quad quad_{};
    float inverseHomography_[9] = {};
    float edges_[12] = {};  // per edge a, b, c: a x + b y + c = distance inside, camera pixels
    char lastError_[128] = "";
};

}  // namespace render
