#include "render/overlay_catalogue.hpp"

#include "overlay_obj_file.hpp"
#include "overlay_texture_file.hpp"
#include "vision/bounded_file.hpp"
#include "vision/face_fit.hpp"
#include "vision/input_limits.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace render {

namespace {

constexpr const char* kKindNames[] = {"hat", "glasses", "other"};
constexpr const char* kAnchorNames[] = {"eye_midpoint", "nose_bridge", "forehead_top",
                                        "head_top",     "upper_lip",   "chin"};
constexpr const char* kMeasureNames[] = {"interocular", "face_width"};

/// Builds the one-line errors: "<file>:<line>: overlay '<name>': <why>".
class Errors {
public:
    explicit Errors(std::string file) : file_(std::move(file)) {}
    void setOverlay(std::string name) { overlay_ = std::move(name); }

    [[noreturn]] void fail(const toml::source_region& where, const std::string& why) const
    {
        std::string line = "overlay catalogue " + file_;
        if (where.begin.line > 0)
            line += ":" + std::to_string(where.begin.line);
        line += ": ";
        if (!overlay_.empty())
            line += "overlay '" + overlay_ + "': ";
        throw std::runtime_error(line + why);
    }

private:
    std::string file_;
    std::string overlay_;
};

template <std::size_t N>
int pickName(const toml::table& table, const char* key, const char* const (&names)[N],
             const Errors& errors, bool required, int fallback)
{
    const toml::node* node = table.get(key);
    if (node == nullptr) {
        if (required)
            errors.fail(table.source(), std::string("missing key '") + key + "'");
        return fallback;
    }
    std::string allowed;
    for (std::size_t i = 0; i < N; ++i) {
        if (i > 0)
            allowed += '|';
        allowed += names[i];
    }
    const auto* text = node->as_string();
    if (text == nullptr)
        errors.fail(node->source(), std::string(key) + " must be a string, one of " + allowed);
    for (std::size_t i = 0; i < N; ++i)
        if (text->get() == names[i])
            return static_cast<int>(i);
    errors.fail(node->source(),
                std::string(key) + " must be one of " + allowed + ", not '" + text->get() + "'");
}

float number(const toml::node& node, const char* key, const Errors& errors)
{
    if (const auto v = node.value<double>(); v && std::isfinite(*v))
        return static_cast<float>(*v);
    errors.fail(node.source(), std::string(key) + " must be a number");
}

float optionalNumber(const toml::table& table, const char* key, float fallback, float lo, float hi,
                     const Errors& errors)
{
    const toml::node* node = table.get(key);
    if (node == nullptr)
        return fallback;
    const float v = number(*node, key, errors);
    if (v < lo || v > hi) {
        std::ostringstream why;
        why << key << " must be in [" << lo << ", " << hi << "], not " << v;
        errors.fail(node->source(), why.str());
    }
    return v;
}

template <std::size_t N>
std::array<float, N> optionalVector(const toml::table& table, const char* key,
                                    std::array<float, N> fallback, float lo, float hi,
                                    const Errors& errors)
{
    const toml::node* node = table.get(key);
    if (node == nullptr)
        return fallback;
    const toml::array* array = node->as_array();
    if (array == nullptr || array->size() != N)
        errors.fail(node->source(),
                    std::string(key) + " must be an array of " + std::to_string(N) + " numbers");
    std::array<float, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        out[i] = number(*array->get(i), key, errors);
        if (out[i] < lo || out[i] > hi) {
            std::ostringstream why;
            why << key << " values must be in [" << lo << ", " << hi << "], not " << out[i];
            errors.fail(node->source(), why.str());
        }
    }
    return out;
}

std::string requiredString(const toml::table& table, const char* key, const Errors& errors)
{
    const toml::node* node = table.get(key);
    if (node == nullptr)
        errors.fail(table.source(), std::string("missing key '") + key + "'");
    const auto* text = node->as_string();
    if (text == nullptr || text->get().empty())
        errors.fail(node->source(), std::string(key) + " must be a non-empty string");
    return text->get();
}

bool validName(const std::string& name)
{
    for (const char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
            return false;
    return !name.empty();
}

OverlayMesh readMesh(const toml::table& table, const std::filesystem::path& base,
                     const Errors& errors)
{
    OverlayMesh mesh;
    const std::string obj = requiredString(table, "obj", errors);
    std::vector<std::string> objects;
    if (const toml::node* node = table.get("objects")) {
        const toml::array* array = node->as_array();
        if (array == nullptr || array->empty())
            errors.fail(node->source(), "objects must be a non-empty array of strings");
        for (const toml::node& item : *array) {
            const auto* name = item.as_string();
            if (name == nullptr)
                errors.fail(item.source(), "objects must be a non-empty array of strings");
            objects.push_back(name->get());
        }
    }
    mesh.material.color = optionalVector<4>(table, "color", {1.f, 1.f, 1.f, 1.f}, 0.f, 1.f, errors);
    mesh.material.shininess = optionalNumber(table, "shininess", 0.f, 0.f, 1000.f, errors);
    std::optional<bool> doubleSided;
    if (const toml::node* node = table.get("double_sided")) {
        doubleSided = node->value<bool>();
        if (!doubleSided)
            errors.fail(node->source(), "double_sided must be true or false");
    }
    if (const toml::node* node = table.get("texture")) {
        const auto* name = node->as_string();
        if (name == nullptr || name->get().empty())
            errors.fail(node->source(), "texture must be a PNG path relative to the catalogue");
        try {
            mesh.texture = readTextureFile((base / name->get()).string());
        } catch (const std::runtime_error& e) {
            errors.fail(node->source(), e.what());
        }
    }
    mesh.source = obj;
    if (!objects.empty()) {
        mesh.source += "[";
        for (std::size_t i = 0; i < objects.size(); ++i) {
            if (i > 0)
                mesh.source += ',';
            mesh.source += objects[i];
        }
        mesh.source += "]";
    }
    for (const auto& [key, value] : table)
        if (key != "obj" && key != "objects" && key != "color" && key != "texture" &&
            key != "shininess" && key != "double_sided")
            errors.fail(value.source(), "unknown mesh key '" + std::string(key.str()) + "'");
    try {
        indexTriangles(readObjTriangles((base / obj).string(), obj, objects, !mesh.texture.empty()),
                       mesh, obj);
    } catch (const std::runtime_error& e) {
        errors.fail(table.source(), e.what());
    }
    // Closed meshes are culled unless the catalogue says otherwise; false trusts the file.
    const bool closed = !(doubleSided && *doubleSided) && orientClosedMesh(mesh);
    mesh.material.doubleSided = doubleSided ? *doubleSided : !closed;
    return mesh;
}

// One [[overlay.follow]] table (FORMAT.md): which animation unit, and what it does per unit.
OverlayFollow readFollow(const toml::table& table, const Errors& errors)
{
    for (const auto& [key, value] : table) {
        if (key != "unit" && key != "offset" && key != "rotation" && key != "stretch")
            errors.fail(value.source(), "unknown follow key '" + std::string(key.str()) + "'");
    }
    OverlayFollow follow;
    const std::string unit = requiredString(table, "unit", errors);
    const auto& names = vision::kFaceFitAnimationNames;
    const auto at = std::find(names.begin(), names.end(), unit);
    if (at == names.end()) {
        std::string allowed;
        for (const std::string_view n : names) {
            if (!allowed.empty())
                allowed += '|';
            allowed.append(n);
        }
        errors.fail(table.get("unit")->source(),
                    "follow unit must be one of " + allowed + ", not '" + unit + "'");
    }
    follow.unit = static_cast<int>(at - names.begin());
    follow.offset = optionalVector<3>(table, "offset", {}, -10.f, 10.f, errors);
    follow.rotationDegrees = optionalVector<3>(table, "rotation", {}, -90.f, 90.f, errors);
    follow.stretch = optionalVector<3>(table, "stretch", {}, -2.f, 2.f, errors);
    return follow;
}

std::vector<OverlayFollow> readFollows(const toml::table& table, const Errors& errors)
{
    std::vector<OverlayFollow> follows;
    const toml::node* node = table.get("follow");
    if (node == nullptr)
        return follows;
    const toml::array* array = node->as_array();
    if (array == nullptr || !array->is_array_of_tables())
        errors.fail(node->source(), "follow must be an array of tables ([[overlay.follow]])");
    if (array->size() > kMaxOverlayFollows)
        errors.fail(node->source(), "more than " + std::to_string(kMaxOverlayFollows) +
                                        " [[overlay.follow]] tables");
    for (const toml::node& item : *array) {
        const OverlayFollow f = readFollow(*item.as_table(), errors);
        for (const OverlayFollow& other : follows)
            if (other.unit == f.unit)
                errors.fail(
                    item.source(),
                    "a second follow of unit '" +
                        std::string(
                            vision::kFaceFitAnimationNames[static_cast<std::size_t>(f.unit)]) +
                        "'");
        follows.push_back(f);
    }
    return follows;
}

Overlay readOverlay(const toml::table& table, const std::filesystem::path& base, Errors& errors)
{
    Overlay overlay;
    errors.setOverlay("");
    overlay.name = requiredString(table, "name", errors);
    if (!validName(overlay.name))
        errors.fail(table.get("name")->source(),
                    "name '" + overlay.name + "' must be lower-case letters, digits, _ or -");
    errors.setOverlay(overlay.name);
    for (const auto& [key, value] : table) {
        static constexpr const char* kKeys[] = {"name",   "kind",     "anchor", "measure", "scale",
                                                "offset", "rotation", "follow", "mesh"};
        bool known = false;
        for (const char* k : kKeys)
            known = known || key == k;
        if (!known)
            errors.fail(value.source(), "unknown key '" + std::string(key.str()) + "'");
    }
    overlay.kind = static_cast<OverlayKind>(pickName(table, "kind", kKindNames, errors, true, 0));
    overlay.anchor =
        static_cast<OverlayAnchor>(pickName(table, "anchor", kAnchorNames, errors, true, 0));
    overlay.measure =
        static_cast<HeadMeasure>(pickName(table, "measure", kMeasureNames, errors, true, 0));
    overlay.scale = optionalNumber(table, "scale", 1.f, 1e-3f, 1e3f, errors);
    overlay.offset = optionalVector<3>(table, "offset", {}, -100.f, 100.f, errors);
    overlay.rotationDegrees = optionalVector<3>(table, "rotation", {}, -360.f, 360.f, errors);
    overlay.follows = readFollows(table, errors);
    const toml::node* meshes = table.get("mesh");
    if (meshes == nullptr)
        errors.fail(table.source(), "no [[overlay.mesh]]");
    const toml::array* array = meshes->as_array();
    if (array == nullptr || array->empty() || !array->is_array_of_tables())
        errors.fail(meshes->source(), "mesh must be an array of tables ([[overlay.mesh]])");
    std::size_t triangles = 0;
    for (const toml::node& mesh : *array) {
        overlay.meshes.push_back(readMesh(*mesh.as_table(), base, errors));
        triangles += overlay.meshes.back().indices.size() / 3;
    }
    // The software renderer's budget: every face may wear the overlay (FORMAT.md).
    if (triangles > static_cast<std::size_t>(vision::limits::kMaxOverlayTriangles))
        errors.fail(meshes->source(), std::to_string(triangles) +
                                          " triangles, over the budget of " +
                                          std::to_string(vision::limits::kMaxOverlayTriangles) +
                                          " per overlay (all its meshes)");
    return overlay;
}

}  // namespace

const char* overlayKindName(OverlayKind kind) noexcept
{
    return kKindNames[static_cast<int>(kind)];
}
const char* overlayAnchorName(OverlayAnchor anchor) noexcept
{
    return kAnchorNames[static_cast<int>(anchor)];
}
const char* headMeasureName(HeadMeasure measure) noexcept
{
    return kMeasureNames[static_cast<int>(measure)];
}

OverlayCatalogue OverlayCatalogue::load(const std::string& catalogueToml)
{
    Errors errors(catalogueToml);
    const vision::BoundedFile file =
        vision::readBoundedFile(catalogueToml, vision::limits::kCatalogueBytes);
    if (file.status == vision::BoundedFile::Status::Missing)
        errors.fail({}, "no such file");
    if (file.status != vision::BoundedFile::Status::Ok)
        errors.fail({}, file.problem);
    toml::table root;
    try {
        root = toml::parse(file.text, catalogueToml);
    } catch (const toml::parse_error& e) {
        errors.fail(e.source(), std::string(e.description()));
    }
    const toml::node* version = root.get("version");
    if (version == nullptr || version->value<std::int64_t>() != std::int64_t{1})
        errors.fail(version ? version->source() : root.source(), "version must be 1");
    for (const auto& [key, value] : root)
        if (key != "version" && key != "overlay")
            errors.fail(value.source(), "unknown key '" + std::string(key.str()) + "'");
    const toml::array* overlays = root["overlay"].as_array();
    if (overlays == nullptr || overlays->empty() || !overlays->is_array_of_tables())
        errors.fail(root.source(), "no [[overlay]] tables");

    OverlayCatalogue catalogue;
    catalogue.path_ = catalogueToml;
    const std::filesystem::path base = std::filesystem::path(catalogueToml).parent_path();
    for (const toml::node& node : *overlays) {
        Overlay overlay = readOverlay(*node.as_table(), base, errors);
        if (catalogue.find(overlay.name) >= 0)
            errors.fail(node.source(), "a second overlay with this name");
        catalogue.overlays_.push_back(std::move(overlay));
    }
    return catalogue;
}

int OverlayCatalogue::find(std::string_view name) const noexcept
{
    for (std::size_t i = 0; i < overlays_.size(); ++i)
        if (overlays_[i].name == name)
            return static_cast<int>(i);
    return -1;
}

}  // namespace render
