#pragma once
// Reading an overlay mesh's PNG texture (assets/overlays/FORMAT.md), bounded: the file through
// vision::readBoundedFile, the picture's size checked from its header before anything is decoded.
// Private to the overlay catalogue.

#include "render/overlay_catalogue.hpp"

#include <string>

namespace render {

/// The PNG at `path` as RGBA8, bottom-up. Throws std::runtime_error("texture PATH: why").
OverlayTexture readTextureFile(const std::string& path);

}  // namespace render
