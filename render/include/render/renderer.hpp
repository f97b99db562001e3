#pragma once
// Renderer: draws one mirror frame with GLES2 into the framebuffer the display has bound.
// Layers, bottom to top: the camera frame (mirrored left-right, full screen, aspect kept), the
// overlay layers in the order added, the diagnostics HUD.

#include "render/overlay_layer.hpp"
#include "vision/image.hpp"

#include <array>
#include <cstddef>
#include <memory>

namespace render {

namespace detail {
class RotatedTarget;
}

/// How the camera image fills a screen of another aspect ratio.
enum class Fit {
    Cover,    ///< fill the screen, crop the overflow (a mirror shows no bars)
    Contain,  ///< show the whole image, black bars where the aspects differ
};

struct RendererOptions {
    bool mirror = true;  ///< draw left-right flipped, as a mirror shows a person
    Fit fit = Fit::Cover;
    bool hud = true;  ///< draw the diagnostics text (fps etc.) in the top-left corner
    /// Turns the whole picture clockwise on the display by 0, 90, 180 or 270 degrees: for a panel
    /// mounted on its side (portrait) or upside down. Everything drawn turns with it.
    int rotation = 0;
};

class Renderer {
public:
    static constexpr std::size_t kMaxLayers = 8;

    /// Creates the GL objects for frames of this size and format (RGB24, BGR24, XRGB8888, Gray8).
    /// Needs a current GLES2 context; throws std::runtime_error with one line on failure.
    Renderer(vision::Size videoSize, vision::PixelFormat videoFormat,
             const RendererOptions& options);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Adds a layer drawn over the video (start-up only; at most kMaxLayers). Not owned.
    void addLayer(OverlayLayer* layer);
    void setHudVisible(bool visible) noexcept { options_.hud = visible; }
    bool hudVisible() const noexcept { return options_.hud; }
    const RendererOptions& options() const noexcept { return options_; }

    /// Uploads `frame` and draws everything into the bound framebuffer of the given size (the
    /// display's; with a rotation the picture is drawn turned, at the turned size).
    /// `hudText` may hold several lines separated by '\n' (printable ASCII). An empty `frame`
    /// redraws the last uploaded picture (black before the first). Never allocates.
    /// False on a GL error (lastError() says which).
    bool draw(const vision::ConstImageView& frame, int viewportWidth, int viewportHeight,
              const char* hudText) noexcept;

    /// Draws a calm full-screen message instead of the video (dark background, centred text), e.g.
    /// "camera unavailable" while the source is lost, so the screen never shows a frozen frame.
    /// Never allocates; false on a GL error.
    bool drawMessage(const char* message, int viewportWidth, int viewportHeight) noexcept;
    /// The image-to-NDC mapping used for the last draw (also handed to layers).
    const LayerContext& layerContext() const noexcept { return context_; }
    const char* lastError() const noexcept { return lastError_; }

private:
    bool drawUpright(const vision::ConstImageView& frame, int viewportWidth, int viewportHeight,
                     const char* hudText) noexcept;
    bool drawMessageUpright(const char* message, int viewportWidth, int viewportHeight) noexcept;
    template <typename Draw>
    bool drawTurned(int viewportWidth, int viewportHeight, Draw&& draw) noexcept;

    struct Gl;  // GL object names; defined in renderer.cpp so this header needs no GL header
    std::unique_ptr<Gl> gl_;
    std::unique_ptr<detail::RotatedTarget> rotated_;  // null without a rotation
    vision::Size videoSize_;
    vision::PixelFormat videoFormat_;
    RendererOptions options_;
    std::array<OverlayLayer*, kMaxLayers> layers_{};
    std::size_t layerCount_ = 0;
    LayerContext context_;
    char lastError_[128] = "";
};

}  // namespace render
