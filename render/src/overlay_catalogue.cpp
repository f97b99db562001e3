#include "render/overlay_catalogue.hpp"

#include <png.h>
#include <tiny_obj_loader.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace render {

namespace {

constexpr const char* kKindNames[] = {"hat", "glasses", "other"};
constexpr const char* kAnchorNames[] = {"eye_midpoint", "nose_bridge", "forehead_top", "head_top"};
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

/// The first line of a tinyobjloader message (it may hold several).
std::string firstLine(const std::string& text)
{
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
        line.pop_back();
    return line;
}

OverlayTexture readPng(const std::string& path, const toml::source_region& where,
                       const Errors& errors)
{
    png_image image;
    std::memset(&image, 0, sizeof(image));
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str()))
        errors.fail(where, "texture " + path + ": " + image.message);
    image.format = PNG_FORMAT_RGBA;
    OverlayTexture texture;
    texture.width = static_cast<int>(image.width);
    texture.height = static_cast<int>(image.height);
    texture.rgba.resize(PNG_IMAGE_SIZE(image));
    // A negative row stride stores the picture bottom-up, as GL and OBJ texture coordinates want.
    const auto stride = -static_cast<png_int_32>(PNG_IMAGE_ROW_STRIDE(image));
    if (!png_image_finish_read(&image, nullptr, texture.rgba.data(), stride, nullptr)) {
        const std::string why = image.message;
        png_image_free(&image);
        errors.fail(where, "texture " + path + ": " + why);
    }
    return texture;
}

/// Triangles of the selected objects of an OBJ file, with flat normals where it has none.
std::vector<OverlayVertex> readObj(const std::string& path, const std::string& shownPath,
                                   const std::vector<std::string>& objects, bool needUv,
                                   const toml::source_region& where, const Errors& errors)
{
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = "/nonexistent/";  // materials come from the catalogue
    tinyobj::ObjReader reader;
    if (!std::filesystem::is_regular_file(path))
        errors.fail(where, "OBJ " + shownPath + ": no such file");
    if (!reader.ParseFromFile(path, config))
        errors.fail(where, "OBJ " + shownPath + ": " + firstLine(reader.Error()));
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    std::vector<bool> used(objects.size(), false);
    std::vector<OverlayVertex> vertices;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        if (!objects.empty()) {
            bool wanted = false;
            for (std::size_t i = 0; i < objects.size(); ++i)
                if (objects[i] == shape.name)
                    wanted = used[i] = true;
            if (!wanted)
                continue;
        }
        const std::vector<tinyobj::index_t>& indices = shape.mesh.indices;
        for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
            OverlayVertex triangle[3];
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& index = indices[t + static_cast<std::size_t>(k)];
                const auto vi = static_cast<std::size_t>(index.vertex_index);
                if (index.vertex_index < 0 || 3 * vi + 2 >= attrib.vertices.size())
                    errors.fail(where, "OBJ " + shownPath + ": a face" +
                                           (shape.name.empty() ? "" : " of '" + shape.name + "'") +
                                           " uses vertex " +
                                           std::to_string(index.vertex_index + 1) +
                                           " but the file has " +
                                           std::to_string(attrib.vertices.size() / 3));
                OverlayVertex& v = triangle[k];
                for (int c = 0; c < 3; ++c)
                    v.position[c] = attrib.vertices[3 * vi + static_cast<std::size_t>(c)];
                const auto ni = static_cast<std::size_t>(index.normal_index);
                if (index.normal_index >= 0 && 3 * ni + 2 < attrib.normals.size()) {
                    float length = 0.f;
                    for (int c = 0; c < 3; ++c) {
                        v.normal[c] = attrib.normals[3 * ni + static_cast<std::size_t>(c)];
                        length += v.normal[c] * v.normal[c];
                    }
                    length = std::sqrt(length);
                    for (float& c : v.normal)
                        c = length > 0.f ? c / length : 0.f;
                } else {
                    v.normal[0] = v.normal[1] = v.normal[2] = 0.f;
                }
                const auto ti = static_cast<std::size_t>(index.texcoord_index);
                if (index.texcoord_index >= 0 && 2 * ti + 1 < attrib.texcoords.size()) {
                    v.uv[0] = attrib.texcoords[2 * ti];
                    v.uv[1] = attrib.texcoords[2 * ti + 1];
                } else if (needUv) {
                    errors.fail(where, "OBJ " + shownPath + ": object '" + shape.name +
                                           "' has faces without texture coordinates (vt), "
                                           "but the mesh has a texture");
                } else {
                    v.uv[0] = v.uv[1] = 0.f;
                }
            }
            // Flat normal where the file gives none.
            const float* a = triangle[0].position;
            const float* b = triangle[1].position;
            const float* c = triangle[2].position;
            const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            const float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                          e1[0] * e2[1] - e1[1] * e2[0]};
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (float& x : n)
                x = length > 0.f ? x / length : 0.f;
            if (length == 0.f)
                n[2] = 1.f;
            for (OverlayVertex& v : triangle) {
                if (v.normal[0] == 0.f && v.normal[1] == 0.f && v.normal[2] == 0.f)
                    std::memcpy(v.normal, n, sizeof(n));
                vertices.push_back(v);
            }
        }
    }
    for (std::size_t i = 0; i < objects.size(); ++i)
        if (!used[i])
            errors.fail(where, "OBJ " + shownPath + " has no object or group '" + objects[i] + "'");
    if (vertices.empty())
        errors.fail(where, "OBJ " + shownPath + " has no faces");
    return vertices;
}

/// Shares equal vertices between triangles (GL then shades each once: llvmpipe caches indexed
/// vertices) and makes the 16-bit index list GLES2 draws.
void index(const std::vector<OverlayVertex>& triangles, OverlayMesh& mesh,
           const std::string& shownPath, const toml::source_region& where, const Errors& errors)
{
    struct Key {
        OverlayVertex v;
        bool operator==(const Key& o) const { return std::memcmp(&v, &o.v, sizeof(v)) == 0; }
    };
    struct Hash {
        std::size_t operator()(const Key& k) const
        {
            std::uint32_t words[sizeof(OverlayVertex) / 4];
            std::memcpy(words, &k.v, sizeof(words));
            std::size_t h = 1469598103934665603ull;
            for (const std::uint32_t w : words)
                h = (h ^ w) * 1099511628211ull;
            return h;
        }
    };
    std::unordered_map<Key, std::uint16_t, Hash> seen;
    mesh.vertices.clear();
    mesh.indices.clear();
    mesh.indices.reserve(triangles.size());
    for (const OverlayVertex& v : triangles) {
        const auto [it, added] = seen.try_emplace(Key{v}, static_cast<std::uint16_t>(0));
        if (added) {
            if (mesh.vertices.size() == kMaxMeshVertices)
                errors.fail(where, "OBJ " + shownPath + ": more than " +
                                       std::to_string(kMaxMeshVertices) +
                                       " distinct vertices in one mesh (split it with objects)");
            it->second = static_cast<std::uint16_t>(mesh.vertices.size());
            mesh.vertices.push_back(v);
        }
        mesh.indices.push_back(it->second);
    }
}

/// True when the mesh is closed (every edge, by position, shared by exactly two triangles that
/// run it in opposite directions), after turning each closed piece counter-clockwise seen from
/// outside (positive volume): its back faces can then be culled, which halves the triangles
/// software GL rasterises. False (mesh unchanged) for open surfaces such as a lens or a brim.
bool orientClosedMesh(OverlayMesh& mesh)
{
    // Vertices at the same position are one point (normals and uvs split them).
    struct PositionHash {
        std::size_t operator()(const std::array<float, 3>& p) const
        {
            std::uint32_t w[3];
            std::memcpy(w, p.data(), sizeof(w));
            return (std::size_t{w[0]} * 73856093u) ^ (std::size_t{w[1]} * 19349663u) ^
                   (std::size_t{w[2]} * 83492791u);
        }
    };
    std::unordered_map<std::array<float, 3>, std::uint32_t, PositionHash> ids;
    std::vector<std::uint32_t> point(mesh.vertices.size());
    std::vector<std::array<float, 3>> positions;
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const float* p = mesh.vertices[i].position;
        const auto [it, added] =
            ids.try_emplace({p[0], p[1], p[2]}, static_cast<std::uint32_t>(positions.size()));
        if (added)
            positions.push_back({p[0], p[1], p[2]});
        point[i] = it->second;
    }
    // Union-find of the points into pieces, and the directed edges.
    std::vector<std::uint32_t> parent(positions.size());
    for (std::uint32_t i = 0; i < parent.size(); ++i)
        parent[i] = i;
    auto root = [&](std::uint32_t i) {
        while (parent[i] != i)
            i = parent[i] = parent[parent[i]];
        return i;
    };
    std::unordered_map<std::uint64_t, int> edges;
    auto edge = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; };
    const std::size_t triangles = mesh.indices.size() / 3;
    std::vector<bool> degenerate(triangles, false);
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t a = point[mesh.indices[3 * t]];
        const std::uint32_t b = point[mesh.indices[3 * t + 1]];
        const std::uint32_t c = point[mesh.indices[3 * t + 2]];
        if (a == b || b == c || c == a) {  // no area: never seen, ignored
            degenerate[t] = true;
            continue;
        }
        if (++edges[edge(a, b)] > 1 || ++edges[edge(b, c)] > 1 || ++edges[edge(c, a)] > 1)
            return false;
        parent[root(b)] = root(a);
        parent[root(c)] = root(a);
    }
    for (const auto& [key, count] : edges)
        if (edges.find((key << 32) | (key >> 32)) == edges.end())
            return false;  // a border edge: open
    // Signed volume of each piece (divergence theorem): positive when it is wound
    // counter-clockwise seen from outside.
    std::unordered_map<std::uint32_t, double> volume;
    for (std::size_t t = 0; t < triangles; ++t) {
        if (degenerate[t])
            continue;
        const auto& a = positions[point[mesh.indices[3 * t]]];
        const auto& b = positions[point[mesh.indices[3 * t + 1]]];
        const auto& c = positions[point[mesh.indices[3 * t + 2]]];
        volume[root(point[mesh.indices[3 * t]])] +=
            double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) +
            double(a[1]) * (double(b[2]) * c[0] - double(b[0]) * c[2]) +
            double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0]);
    }
    for (const auto& [piece, v] : volume)
        if (std::fabs(v) < 1e-12)
            return false;  // flat: no inside
    for (std::size_t t = 0; t < triangles; ++t)
        if (!degenerate[t] && volume[root(point[mesh.indices[3 * t]])] < 0.0)
            std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
    return true;
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
        mesh.texture = readPng((base / name->get()).string(), node->source(), errors);
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
    const std::vector<OverlayVertex> triangles =
        readObj((base / obj).string(), obj, objects, !mesh.texture.empty(), table.source(), errors);
    index(triangles, mesh, obj, table.source(), errors);
    // Closed meshes are culled unless the catalogue says otherwise; false trusts the file.
    const bool closed = !(doubleSided && *doubleSided) && orientClosedMesh(mesh);
    mesh.material.doubleSided = doubleSided ? *doubleSided : !closed;
    return mesh;
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
        static constexpr const char* kKeys[] = {"name",  "kind",   "anchor",   "measure",
                                                "scale", "offset", "rotation", "mesh"};
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
    const toml::node* meshes = table.get("mesh");
    if (meshes == nullptr)
        errors.fail(table.source(), "no [[overlay.mesh]]");
    const toml::array* array = meshes->as_array();
    if (array == nullptr || array->empty() || !array->is_array_of_tables())
        errors.fail(meshes->source(), "mesh must be an array of tables ([[overlay.mesh]])");
    for (const toml::node& mesh : *array)
        overlay.meshes.push_back(readMesh(*mesh.as_table(), base, errors));
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
    if (!std::filesystem::is_regular_file(catalogueToml))
        errors.fail({}, "no such file");
    toml::table root;
    try {
        root = toml::parse_file(catalogueToml);
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
