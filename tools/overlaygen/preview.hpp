#pragma once
// PreviewRenderer: draws overlay OBJ files headless (EGL surfaceless, GLES2) on a stand-in head,
// so the generated models can be looked at without the firmware.

#include "model.hpp"

#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace overlaygen {

/// \class PreviewRenderer
/// Loads a model's OBJ with tinyobjloader (the library the firmware uses), colours its objects
/// with the model's materials and renders it with a perspective camera slightly above the eyes
/// (where the mirror's camera is), Blinn-Phong lighting and back-face culling (so a wrongly
/// wound face would show as a hole). The head proxy ellipsoid is drawn in skin colour for scale.
/// Construction throws std::runtime_error when there is no GL.
class PreviewRenderer {
public:
    PreviewRenderer(int width, int height);
    ~PreviewRenderer();
    PreviewRenderer(const PreviewRenderer&) = delete;
    PreviewRenderer& operator=(const PreviewRenderer&) = delete;

    /// Renders the model in `objFile` with the head turned by `yawDegrees` (positive: the
    /// wearer's left towards the camera), as a BGR image. Throws when the OBJ does not load.
    cv::Mat render(const Model& model, const std::string& objFile, double yawDegrees);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace overlaygen
