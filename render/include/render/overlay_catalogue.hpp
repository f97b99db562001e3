#pragma once
// OverlayCatalogue: the hats, glasses and other 3D overlays the mirror can put on a face, read at
// start-up from a TOML catalogue and Wavefront OBJ meshes (+ optional PNG textures) beside it.
// The format is assets/overlays/FORMAT.md. Everything is loaded into GPU-ready vertex arrays in
// memory (no GL needed: FaceOverlayLayer uploads them), so a bad file fails at start-up with one
// line and never in the frame loop.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace render {

enum class OverlayKind : std::uint8_t { Hat, Glasses, Other };

/// The point of the head model (render/head_model.hpp) an overlay's origin is put on.
enum class OverlayAnchor : std::uint8_t {
    EyeMidpoint,
    NoseBridge,
    ForeheadTop,
    HeadTop,
    UpperLip,
    Chin
};

/// The head measure one model unit is scaled to.
enum class HeadMeasure : std::uint8_t { Interocular, FaceWidth };

const char* overlayKindName(OverlayKind kind) noexcept;
const char* overlayAnchorName(OverlayAnchor anchor) noexcept;
const char* headMeasureName(HeadMeasure measure) noexcept;

/// One vertex of a triangle list, in model axes and units (FORMAT.md): 8 floats, interleaved.
struct OverlayVertex {
    float position[3];
    float normal[3];  ///< unit length
    float uv[2];      ///< OBJ texture coordinates (v = 0 at the bottom of the picture)
};

/// An RGBA8 picture, rows bottom-up (row 0 is v = 0), ready for glTexImage2D.
struct OverlayTexture {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
    bool empty() const noexcept { return width == 0; }
};

/// Distinct vertices one mesh may have (16-bit indices).
inline constexpr std::size_t kMaxMeshVertices = 65535;

struct OverlayMaterial {
    std::array<float, 4> color{1.f, 1.f, 1.f, 1.f};  ///< rgba 0..1, multiplies the texture
    float shininess = 0.f;                           ///< Blinn-Phong exponent, 0 = matt
    /// False: a closed mesh wound counter-clockwise seen from outside; its back faces are culled.
    /// The loader finds closed meshes (and orients them) unless the catalogue says double_sided.
    bool doubleSided = true;
    /// Drawn blended after every opaque mesh (lenses).
    bool transparent() const noexcept { return color[3] < 1.f; }
};

/// One part with one material: indexed triangles (3 indices per triangle), equal vertices shared.
struct OverlayMesh {
    std::string source;                   ///< "glasses/glasses.obj[lenses]", for messages
    std::vector<OverlayVertex> vertices;  ///< at most kMaxMeshVertices
    std::vector<std::uint16_t> indices;   ///< GL_UNSIGNED_SHORT (GLES2 has no 32-bit indices)
    OverlayMaterial material;
    OverlayTexture texture;  ///< empty: no texture
};

/// How an overlay follows one of the fitted face's animation units (§5.3; beyond the
/// dissertation, its future work: overlays that conform to the face as it changes shape). Per
/// unit of the animation value v (vision::FaceFit::animation, named by
/// vision::kFaceFitAnimationNames): the model is stretched along its axes by 1 + v * stretch,
/// turned by v * rotation and moved by v * offset, on top of the overlay's own placement
/// (FORMAT.md). Declared in the catalogue, no code per overlay.
struct OverlayFollow {
    int unit = 0;                            ///< index into vision::kFaceFitAnimationNames
    std::array<float, 3> offset{};           ///< model axes, in units of the measure
    std::array<float, 3> rotationDegrees{};  ///< about model x, then y, then z
    std::array<float, 3> stretch{};          ///< relative growth of x, y, z
};

/// Animation units one overlay may follow (each at most once).
inline constexpr std::size_t kMaxOverlayFollows = 6;

struct Overlay {
    std::string name;
    OverlayKind kind = OverlayKind::Other;
    OverlayAnchor anchor = OverlayAnchor::EyeMidpoint;
    HeadMeasure measure = HeadMeasure::Interocular;
    float scale = 1.f;
    std::array<float, 3> offset{};           ///< model axes, in units of the measure
    std::array<float, 3> rotationDegrees{};  ///< about model x, then y, then z
    std::vector<OverlayFollow> follows;      ///< at most kMaxOverlayFollows, distinct units
    std::vector<OverlayMesh> meshes;
};

class OverlayCatalogue {
public:
    OverlayCatalogue() = default;  ///< empty

    /// Reads `catalogueToml` and every OBJ/PNG it names (paths relative to it). Throws
    /// std::runtime_error with one line naming the file, the TOML line or key (or the OBJ line)
    /// and why, e.g. "overlay catalogue assets/overlays/catalogue.toml:12: overlay 'top_hat':
    /// anchor must be one of eye_midpoint|nose_bridge|forehead_top|head_top|upper_lip|chin, not
    /// 'crown'".
    static OverlayCatalogue load(const std::string& catalogueToml);

    std::span<const Overlay> overlays() const noexcept { return overlays_; }
    int size() const noexcept { return static_cast<int>(overlays_.size()); }
    const Overlay& operator[](int index) const
    {
        return overlays_[static_cast<std::size_t>(index)];
    }
    /// Index of the overlay called `name`, -1 if there is none.
    int find(std::string_view name) const noexcept;
    const std::string& path() const noexcept { return path_; }

private:
    std::string path_;
    std::vector<Overlay> overlays_;
};

}  // namespace render
