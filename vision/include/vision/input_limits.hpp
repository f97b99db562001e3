#pragma once
// What the mirror accepts from the files and frames it is given, in one place. Each bound sits far
// above anything real (the largest real file, image or mesh is named beside it) and far below what
// would exhaust the memory, the stack or a 32-bit product; beyond it the input is refused with one
// line naming the bound. Read through readBoundedFile (bounded_file.hpp).

#include <cstddef>

namespace vision::limits {

inline constexpr std::size_t kMiB = 1024 * 1024;

// ---- files, in bytes -----------------------------------------------------------------------
inline constexpr std::size_t kConfigBytes = 1 * kMiB;      ///< a config is a few kB
inline constexpr std::size_t kStateFileBytes = 64 * 1024;  ///< a colour, an overlay per face
inline constexpr std::size_t kCascadeBytes = 16 * kMiB;   ///< OpenCV's largest face cascade: 0.9 MB
inline constexpr std::size_t kCatalogueBytes = 1 * kMiB;  ///< ours: 3 kB
inline constexpr std::size_t kObjBytes = 16 * kMiB;       ///< ours: under 200 kB
inline constexpr std::size_t kTextureBytes = 16 * kMiB;   ///< a 2048x2048 PNG: a few MB
inline constexpr std::size_t kImageFileBytes = 64 * kMiB;  ///< a 7680x4320 PNG frame: ~50 MB
inline constexpr std::size_t kAamModelBytes =
    64 * kMiB;  ///< ours at 96 px: under 1 MB; 256 px, 100 modes: ~25 MB
// The AAM builder's inputs (tools/aam).
inline constexpr std::size_t kCandideWfmBytes = 1 * kMiB;  ///< CANDIDE-3: 14 kB
inline constexpr std::size_t kAnnotationBytes =
    1 * kMiB;  ///< an IMM .asf: 3 kB; a 68-point .pts: 1 kB

// ---- images, in pixels, checked from the header before decoding ----------------------------
/// A frame or a card picture: no larger than the largest capture the config allows (8K UHD,
/// 7680x4320), either way up.
inline constexpr int kMaxImageSide = 7680;
/// A frame: no smaller than the smallest capture the config allows (the stages scale it down).
inline constexpr int kMinFrameSide = 16;
inline constexpr long long kMaxImagePixels = 7680LL * 4320;
/// An overlay texture: what every GLES2 GPU of the product's class samples (the Pi 4: 4096).
inline constexpr int kMaxTextureSide = 4096;

// ---- meshes --------------------------------------------------------------------------------
/// All meshes of one overlay: the software renderer's budget (assets/overlays/FORMAT.md).
inline constexpr int kMaxOverlayTriangles = 1500;
/// Coordinates of an overlay mesh, in the head units of FORMAT.md (a head is about 2 wide).
inline constexpr float kMaxMeshCoordinate = 1000.f;

}  // namespace vision::limits
