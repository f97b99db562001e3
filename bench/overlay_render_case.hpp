#pragma once
// The 3D overlays' cost per frame (the product's budget: "rendering adds at most 2 ms for 3 faces
// with overlays, headless, software GL"): the renderer drawing a 1280x720 frame into a 1280x720 FBO
// with depth, once with three faces wearing the catalogue's three heaviest overlays and once with
// no face, on a surfaceless EGL context (Mesa llvmpipe here). llvmpipe is told to rasterise on the
// calling thread (LP_NUM_THREADS=0, set before the context exists), so the calling thread's CPU
// time up to glFinish is the whole cost, as on one core of the appliance, and time the loaded
// machine spends on other jobs is not counted.

#include <memory>
#include <string>

namespace bench {

class OverlayRenderCase {
public:
    static constexpr int kFaces = 3;

    /// Sets LP_NUM_THREADS=0 in the environment (before the EGL display is initialised; the
    /// process's later GL contexts rasterise on their calling thread too), then creates the
    /// context, the framebuffer, the renderer and the overlay layer with the catalogue at
    /// `catalogueToml`. Throws std::runtime_error with one line on failure.
    explicit OverlayRenderCase(const std::string& catalogueToml, int width = 1280,
                               int height = 720);
    ~OverlayRenderCase();
    OverlayRenderCase(const OverlayRenderCase&) = delete;
    OverlayRenderCase& operator=(const OverlayRenderCase&) = delete;

    /// One frame (video upload, layers, glFinish), with the three faces' overlays or without.
    /// False on a GL error (lastError()).
    bool frame(bool overlays);

    struct Timing {
        double withMs = 0.0;     ///< median thread CPU ms per frame with the 3 overlays
        double withoutMs = 0.0;  ///< median thread CPU ms of the same frame without them
        int triangles = 0;       ///< triangles of the three faces' overlays together
        double addedMs() const { return withMs - withoutMs; }
    };
    /// Alternates `frames` frames of each kind after a warm-up; medians of each (thread CPU
    /// time, CLOCK_THREAD_CPUTIME_ID).
    Timing measure(int frames);

    /// Names of the three faces' overlays, comma separated (heaviest first).
    std::string overlayNames() const;

    const char* lastError() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace bench
