#include "overlay_obj_file.hpp"

#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

namespace render {

namespace {

/// The first line of a tinyobjloader message (it may hold several), printable: it can quote the
/// file.
std::string firstLine(const std::string& text)
{
    std::string line = text.substr(0, std::min(text.find('\n'), std::size_t{200}));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
        line.pop_back();
    for (char& c : line)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            c = '?';
    return line;
}

/// Every number of the v, vt and vn lines is a finite decimal: tinyobjloader reads "nan", "inf"
/// or a typo as 0 without a word, and 1e999 as infinity.
void checkNumbers(const std::string& text, const std::string& shownPath)
{
    std::size_t line = 0;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view row(text.data() + start, end - start);
        start = end + 1;
        ++line;
        if (!(row.starts_with("v ") || row.starts_with("vt ") || row.starts_with("vn ")))
            continue;
        std::size_t at = row.find(' ');
        while (at < row.size()) {
            at = row.find_first_not_of(" \t\r", at);
            if (at == std::string_view::npos)
                break;
            const std::size_t stop = std::min(row.find_first_of(" \t\r", at), row.size());
            float value = 0.f;
            const auto [ptr, ec] = std::from_chars(row.data() + at, row.data() + stop, value);
            if (ec != std::errc() || ptr != row.data() + stop || !std::isfinite(value))
                throw std::runtime_error(
                    "OBJ " + shownPath + ":" + std::to_string(line) + ": '" +
                    firstLine(std::string(row.substr(at, std::min<std::size_t>(stop - at, 32)))) +
                    "' is not a finite number");
            at = stop;
        }
    }
}

/// An OBJ that parsed, with the name it is shown by, for the checks below.
struct ObjFile {
    const tinyobj::attrib_t& attrib;
    const std::string& shownPath;

    [[noreturn]] void fail(const std::string& why) const
    {
        throw std::runtime_error("OBJ " + shownPath + ": " + why);
    }
};

/// The vertex of one face corner: a position in range, its normal (0 when the file has none),
/// its texture coordinates (required when `needUv`).
OverlayVertex cornerVertex(const ObjFile& obj, const tinyobj::shape_t& shape,
                           const tinyobj::index_t& index, bool needUv)
{
    const tinyobj::attrib_t& attrib = obj.attrib;
    const std::string of = shape.name.empty() ? "" : " of '" + shape.name + "'";
    OverlayVertex v{};
    const auto vi = static_cast<std::size_t>(index.vertex_index);
    if (index.vertex_index < 0 || 3 * vi + 2 >= attrib.vertices.size())
        obj.fail("a face" + of + " uses vertex " + std::to_string(index.vertex_index + 1) +
                 " but the file has " + std::to_string(attrib.vertices.size() / 3));
    for (int c = 0; c < 3; ++c) {
        v.position[c] = attrib.vertices[3 * vi + static_cast<std::size_t>(c)];
        if (!(std::fabs(v.position[c]) <= vision::limits::kMaxMeshCoordinate)) {
            std::ostringstream why;
            why << "vertex " << vi + 1 << " has coordinate " << v.position[c]
                << " (allowed: finite, within +-" << vision::limits::kMaxMeshCoordinate << ")";
            obj.fail(why.str());
        }
    }
    const auto ni = static_cast<std::size_t>(index.normal_index);
    if (index.normal_index >= 0 && 3 * ni + 2 < attrib.normals.size()) {
        float length = 0.f;
        for (int c = 0; c < 3; ++c) {
            v.normal[c] = attrib.normals[3 * ni + static_cast<std::size_t>(c)];
            length += v.normal[c] * v.normal[c];
        }
        length = std::sqrt(length);
        // A zero or non-finite normal is taken as none: the face's own is used instead.
        for (float& c : v.normal)
            c = length > 0.f && std::isfinite(length) ? c / length : 0.f;
    }
    const auto ti = static_cast<std::size_t>(index.texcoord_index);
    if (index.texcoord_index >= 0 && 2 * ti + 1 < attrib.texcoords.size()) {
        v.uv[0] = attrib.texcoords[2 * ti];
        v.uv[1] = attrib.texcoords[2 * ti + 1];
        if (!std::isfinite(v.uv[0]) || !std::isfinite(v.uv[1]))
            obj.fail("texture coordinate " + std::to_string(ti + 1) + " is not finite");
    } else if (needUv) {
        obj.fail("object '" + shape.name +
                 "' has faces without texture coordinates (vt), but the mesh has a texture");
    }
    return v;
}

/// The triangle's unit normal, and whether it has area at all.
bool faceNormal(const OverlayVertex (&triangle)[3], float (&n)[3])
{
    const float* a = triangle[0].position;
    const float* b = triangle[1].position;
    const float* c = triangle[2].position;
    const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0.f)) {
        n[0] = n[1] = 0.f;
        n[2] = 1.f;
        return false;
    }
    for (float& x : n)
        x /= length;
    return true;
}

/// Whether `shape` is one of `objects` (all are when it is empty); marks the ones found.
bool wanted(const tinyobj::shape_t& shape, const std::vector<std::string>& objects,
            std::vector<bool>& used)
{
    if (objects.empty())
        return true;
    bool found = false;
    for (std::size_t i = 0; i < objects.size(); ++i)
        if (objects[i] == shape.name)
            found = used[i] = true;
    return found;
}

}  // namespace

std::vector<OverlayVertex> readObjTriangles(const std::string& path, const std::string& shownPath,
                                            const std::vector<std::string>& objects, bool needUv)
{
    const vision::BoundedFile file = vision::readBoundedFile(path, vision::limits::kObjBytes);
    if (file.status == vision::BoundedFile::Status::Missing)
        throw std::runtime_error("OBJ " + shownPath + ": no such file");
    if (file.status != vision::BoundedFile::Status::Ok)
        throw std::runtime_error("OBJ " + shownPath + ": " + file.problem);
    checkNumbers(file.text, shownPath);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // No material text: materials come from the catalogue.
    if (!reader.ParseFromString(file.text, std::string(), config))
        throw std::runtime_error("OBJ " + shownPath + ": " + firstLine(reader.Error()));
    const ObjFile obj{reader.GetAttrib(), shownPath};

    constexpr auto kTriangleBudget = static_cast<std::size_t>(vision::limits::kMaxOverlayTriangles);
    std::vector<bool> used(objects.size(), false);
    std::vector<OverlayVertex> vertices;
    bool anyArea = false;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        if (!wanted(shape, objects, used))
            continue;
        const std::vector<tinyobj::index_t>& indices = shape.mesh.indices;
        for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
            OverlayVertex triangle[3];
            for (int k = 0; k < 3; ++k)
                triangle[k] =
                    cornerVertex(obj, shape, indices[t + static_cast<std::size_t>(k)], needUv);
            float n[3];
            anyArea = faceNormal(triangle, n) || anyArea;
            for (OverlayVertex& v : triangle) {
                if (v.normal[0] == 0.f && v.normal[1] == 0.f && v.normal[2] == 0.f)
                    std::memcpy(v.normal, n, sizeof(n));  // flat normal where the file has none
                vertices.push_back(v);
            }
            // One mesh over the whole overlay's budget is refused as soon as it is seen: a file
            // of millions of faces then costs no more than its parse.
            if (vertices.size() / 3 > kTriangleBudget)
                obj.fail("more than " + std::to_string(kTriangleBudget) +
                         " triangles, the budget of one overlay (all its meshes)");
        }
    }
    for (std::size_t i = 0; i < objects.size(); ++i)
        if (!used[i])
            throw std::runtime_error("OBJ " + shownPath + " has no object or group '" + objects[i] +
                                     "'");
    if (vertices.empty())
        throw std::runtime_error("OBJ " + shownPath + " has no faces");
    if (!anyArea)
        obj.fail("no face has any area (every vertex of each face on one line or point)");
    return vertices;
}

void indexTriangles(const std::vector<OverlayVertex>& triangles, OverlayMesh& mesh,
                    const std::string& shownPath)
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
                throw std::runtime_error("OBJ " + shownPath + ": more than " +
                                         std::to_string(kMaxMeshVertices) +
                                         " distinct vertices in one mesh (split it with objects)");
            it->second = static_cast<std::uint16_t>(mesh.vertices.size());
            mesh.vertices.push_back(v);
        }
        mesh.indices.push_back(it->second);
    }
}

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

}  // namespace render
