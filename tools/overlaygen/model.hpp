#pragma once
// Model: one overlay as the generator builds it (solids in metres, parts, materials, placement),
// and its finished form (welded, with normals) that the OBJ, MTL and catalogue writers print.

#include "mesh.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace overlaygen {

/// Written to the catalogue (which is what the firmware uses) and to the .mtl (for viewers).
struct Material {
    std::string name;
    std::array<double, 4> rgba{1.0, 1.0, 1.0, 1.0};
    double shininess = 0.0;
};

/// One OBJ object (`o name`) drawn with one material. Parts with the same closure group form one
/// watertight surface together (each part alone may be open, e.g. one colour of a striped cone).
struct Part {
    std::string name;
    int material = 0;
    std::string closureGroup;
};

/// \class Model
/// An overlay: what it is, where it sits on the head (catalogue keys, see
/// assets/overlays/FORMAT.md), its materials and parts, and the solids whose triangles are
/// tagged with part indices. Geometry is in metres in the catalogue's model axes (x the wearer's
/// left, y up, z out of the face) with the origin on the anchor; `scale` turns the catalogue's
/// head measure back into metres.
/// One [[overlay.follow]] of the catalogue (FORMAT.md): per unit of a fitted animation value, a
/// move (OBJ units, here metres), a turn (degrees) and a relative stretch along the model axes.
struct Follow {
    std::string unit;  ///< vision::kFaceFitAnimationNames, e.g. "upper_lip_raiser"
    std::array<double, 3> offset{0.0, 0.0, 0.0};
    std::array<double, 3> rotationDegrees{0.0, 0.0, 0.0};
    std::array<double, 3> stretch{0.0, 0.0, 0.0};
};

struct Model {
    std::string name;
    std::string kind;
    std::string anchor;
    std::string measure;
    double scale = 1.0;
    std::array<double, 3> rotationDegrees{0.0, 0.0, 0.0};
    std::vector<Follow> follows;
    std::string description;
    std::vector<Material> materials;
    std::vector<Part> parts;
    std::vector<Solid> solids;

    /// Adds a material and returns its index.
    int addMaterial(const std::string& materialName, std::array<double, 4> rgba, double shininess);
    /// Adds a part and returns its index (closure group = its name when empty).
    int addPart(const std::string& partName, int material, const std::string& closureGroup = "");
};

/// Positions on a 10 micrometre grid, normals on a 1e-4 grid: what the OBJ holds exactly.
inline constexpr double kPositionUnit = 1e-5;
inline constexpr double kNormalUnit = 1e-4;

/// A model welded on the position grid (identical rounded positions become one vertex, which
/// closes poles and cap centres), with degenerate triangles dropped and crease-aware,
/// angle-weighted corner normals. Indices are 0-based into the pools.
struct FinishedMesh {
    struct Face {
        int part = 0;
        std::array<int, 3> v{};
        std::array<int, 3> n{};
    };
    std::vector<std::array<std::int64_t, 3>> positions;
    std::vector<std::array<std::int64_t, 3>> normals;
    std::vector<Face> faces;
};

FinishedMesh finish(const Model& model);

/// The OBJ text (names its .mtl as <name>.mtl), the MTL text, and the model's catalogue tables.
std::string objText(const Model& model, const FinishedMesh& mesh);
std::string mtlText(const Model& model);
std::string catalogueEntry(const Model& model);
/// The generated block of catalogue.toml for these models, between its marker lines.
std::string catalogueBlock(const std::vector<Model>& models);
/// catalogue.toml with the generated block replaced in `existing` (hand-written overlays outside
/// the block stay); a new catalogue when `existing` is empty or has no block.
std::string mergeCatalogue(const std::string& existing, const std::string& block);

/// Relative paths of a model's files inside assets/overlays/.
std::string objPath(const Model& model);
std::string mtlPath(const Model& model);

}  // namespace overlaygen
