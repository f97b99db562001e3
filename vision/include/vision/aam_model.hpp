#pragma once
// AamModel: the Active Appearance Model the runtime fit loads (§5; dissertation 5.3.1), as plain
// data, and its file (docs/aam-model-format.md): built offline by `aam-build model`, read at
// start-up through readBoundedFile. Nothing here runs per frame; the fit converts what it needs
// (fixed point, steepest-descent images) once when it is built.
//
// Frame: the mean appearance's pixels, x right, y down, the mean shape s0 scaled into it. Vectors
// of 2D shapes are (x0 y0 x1 y1 ...) as eq. 41; mode k of a model with D values per mode starts at
// index k * D.

#include "vision/candide_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vision {

/// One pixel of the mean appearance: where it is in the frame and the mesh triangle it lies in
/// (the pixel->triangle table the warp walks; pixels outside every triangle are not listed).
struct AppearancePixel {
    std::uint16_t x = 0, y = 0;
    std::uint16_t triangle = 0;  ///< index into AamModel::mesh.triangles
};

struct AamModel {
    CandideMesh mesh;  ///< the tracked cut of CANDIDE-3 (its units kept, in parameter order)

    // The 2D shape model, eq. 42, in frame pixels.
    std::vector<float> meanShape;       ///< s0: 2 * vertices
    std::vector<float> shapeModes;      ///< s_i: orthonormal, 2 * vertices each
    std::vector<float> shapeVariances;  ///< of each mode, largest first (frame pixels squared)

    // The appearance model, eq. 43, over `pixels` in their order.
    int frameWidth = 0, frameHeight = 0;
    std::vector<AppearancePixel> pixels;
    std::vector<float> meanAppearance;       ///< A0: zero mean, unit variance over the pixels
    std::vector<float> appearanceModes;      ///< A_i: orthonormal, one value per pixel each
    std::vector<float> appearanceVariances;  ///< of each mode, largest first

    std::size_t shapeModeCount() const noexcept { return shapeVariances.size(); }
    std::size_t appearanceModeCount() const noexcept { return appearanceVariances.size(); }
};

/// The file's first bytes and the one version this build reads and writes.
inline constexpr char kAamModelMagic[8] = {'M', 'I', 'R', 'R', 'A', 'A', 'M', '\0'};
inline constexpr std::uint32_t kAamModelVersion = 1;

/// The model as the bytes of its file. Throws std::invalid_argument (one line) for a model whose
/// parts disagree in size or exceed the format's bounds, so nothing unreadable is written.
std::string encodeAamModel(const AamModel& model);

struct AamModelFile {
    bool ok = false;
    AamModel model;       ///< when ok
    std::string problem;  ///< when not: one line without the path, e.g. "truncated: ..."
};

/// Parses the bytes of a model file: magic, version, sizes, checksum and every index checked.
AamModelFile decodeAamModel(std::span<const std::byte> bytes);

/// Reads `path` with readBoundedFile (limits::kAamModelBytes) and decodes it; `problem` then
/// starts with the path.
AamModelFile loadAamModel(const std::string& path);

}  // namespace vision
