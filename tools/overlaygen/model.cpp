#include "model.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>
#include <stdexcept>

namespace overlaygen {

namespace {

using Key = std::array<std::int64_t, 3>;

Key quantize(const Vec3& v, double unit)
{
    Key key{std::llround(v.x() / unit), std::llround(v.y() / unit), std::llround(v.z() / unit)};
    return key;
}

Vec3 dequantize(const Key& key, double unit)
{
    return Vec3(static_cast<double>(key[0]), static_cast<double>(key[1]),
                static_cast<double>(key[2])) *
           unit;
}

/// Fixed-point text of value * 10^-decimals without going through printf's float rounding
/// (and never "-0.000").
std::string fixed(std::int64_t value, int decimals)
{
    std::int64_t scale = 1;
    for (int k = 0; k < decimals; ++k)
        scale *= 10;
    const bool negative = value < 0;
    const std::int64_t magnitude = negative ? -value : value;
    char text[48];
    std::snprintf(text, sizeof text, "%s%lld.%0*lld", negative ? "-" : "",
                  static_cast<long long>(magnitude / scale), decimals,
                  static_cast<long long>(magnitude % scale));
    return text;
}

std::string number(double value, int decimals)
{
    return fixed(std::llround(value * std::pow(10.0, decimals)), decimals);
}

/// Interns keys in order of first appearance (deterministic output).
struct Pool {
    std::map<Key, int> index;
    std::vector<Key> keys;
    int add(const Key& key)
    {
        const auto [it, inserted] = index.emplace(key, static_cast<int>(keys.size()));
        if (inserted)
            keys.push_back(key);
        return it->second;
    }
};

}  // namespace

int Model::addMaterial(const std::string& materialName, std::array<double, 4> rgba,
                       double shininess)
{
    materials.push_back({materialName, rgba, shininess});
    return static_cast<int>(materials.size()) - 1;
}

int Model::addPart(const std::string& partName, int material, const std::string& closureGroup)
{
    parts.push_back({partName, material, closureGroup.empty() ? partName : closureGroup});
    return static_cast<int>(parts.size()) - 1;
}

FinishedMesh finish(const Model& model)
{
    Pool positionPool;
    Pool normalPool;
    FinishedMesh out;
    for (const Solid& solid : model.solids) {
        // Weld on the output grid, so what is computed here is what the file says.
        Pool local;
        std::vector<int> remap(solid.positions.size());
        for (std::size_t k = 0; k < solid.positions.size(); ++k)
            remap[k] = local.add(quantize(solid.positions[k], kPositionUnit));
        std::vector<Vec3> points;
        for (const Key& key : local.keys)
            points.push_back(dequantize(key, kPositionUnit));

        struct Tri {
            std::array<int, 3> v;
            int part;
            Vec3 normal;
        };
        std::vector<Tri> tris;
        for (const Triangle& t : solid.triangles) {
            const std::array<int, 3> v{remap[static_cast<std::size_t>(t.v[0])],
                                       remap[static_cast<std::size_t>(t.v[1])],
                                       remap[static_cast<std::size_t>(t.v[2])]};
            if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
                continue;
            const Vec3 cross =
                (points[static_cast<std::size_t>(v[1])] - points[static_cast<std::size_t>(v[0])])
                    .cross(points[static_cast<std::size_t>(v[2])] -
                           points[static_cast<std::size_t>(v[0])]);
            if (cross.norm() < 1e-13)
                continue;  // sliver of a pole or a collapsed cap
            tris.push_back({v, t.part, cross.normalized()});
        }

        // Corner normals: angle-weighted mean of the faces around the vertex that lie within
        // the crease angle of this face (sharp edges stay sharp, curved surfaces smooth).
        std::vector<std::vector<std::pair<int, int>>> around(points.size());
        for (std::size_t f = 0; f < tris.size(); ++f)
            for (int c = 0; c < 3; ++c)
                around[static_cast<std::size_t>(tris[f].v[static_cast<std::size_t>(c)])]
                    .emplace_back(static_cast<int>(f), c);
        const auto cornerAngle = [&](const Tri& t, int c) {
            const Vec3& p = points[static_cast<std::size_t>(t.v[static_cast<std::size_t>(c)])];
            const Vec3 a =
                points[static_cast<std::size_t>(t.v[static_cast<std::size_t>((c + 1) % 3)])] - p;
            const Vec3 b =
                points[static_cast<std::size_t>(t.v[static_cast<std::size_t>((c + 2) % 3)])] - p;
            return std::atan2(a.cross(b).norm(), a.dot(b));
        };
        const double cosCrease = std::cos(solid.creaseDegrees * std::numbers::pi / 180.0);
        std::vector<int> globalIndex(points.size());
        for (std::size_t k = 0; k < points.size(); ++k)
            globalIndex[k] = positionPool.add(local.keys[k]);
        for (const Tri& t : tris) {
            FinishedMesh::Face face;
            face.part = t.part;
            for (int c = 0; c < 3; ++c) {
                const int v = t.v[static_cast<std::size_t>(c)];
                Vec3 sum = Vec3::Zero();
                for (const auto& [f, corner] : around[static_cast<std::size_t>(v)]) {
                    const Tri& other = tris[static_cast<std::size_t>(f)];
                    if (other.normal.dot(t.normal) >= cosCrease)
                        sum += other.normal * cornerAngle(other, corner);
                }
                const Vec3 normal = sum.norm() > 1e-12 ? sum.normalized() : t.normal;
                face.v[static_cast<std::size_t>(c)] = globalIndex[static_cast<std::size_t>(v)];
                face.n[static_cast<std::size_t>(c)] = normalPool.add(quantize(normal, kNormalUnit));
            }
            out.faces.push_back(face);
        }
    }
    out.positions = positionPool.keys;
    out.normals = normalPool.keys;
    return out;
}

std::string objPath(const Model& model)
{
    return model.name + "/" + model.name + ".obj";
}

std::string mtlPath(const Model& model)
{
    return model.name + "/" + model.name + ".mtl";
}

std::string objText(const Model& model, const FinishedMesh& mesh)
{
    std::string text;
    text += "# " + model.name + ": " + model.description + "\n";
    text += "# Generated by tools/overlaygen (cmake --build <build> --target overlay-assets);\n";
    text += "# do not edit. Metres; x = wearer's left, y up, z out of the face; origin on the\n";
    text += "# catalogue anchor '" + model.anchor + "'. Materials: catalogue.toml.\n";
    text += "mtllib " + model.name + ".mtl\n";
    for (const Key& p : mesh.positions)
        text += "v " + fixed(p[0], 5) + " " + fixed(p[1], 5) + " " + fixed(p[2], 5) + "\n";
    for (const Key& n : mesh.normals)
        text += "vn " + fixed(n[0], 4) + " " + fixed(n[1], 4) + " " + fixed(n[2], 4) + "\n";
    for (std::size_t part = 0; part < model.parts.size(); ++part) {
        const Part& p = model.parts[part];
        text += "o " + p.name + "\n";
        text += "usemtl " + model.materials[static_cast<std::size_t>(p.material)].name + "\n";
        for (const FinishedMesh::Face& f : mesh.faces) {
            if (f.part != static_cast<int>(part))
                continue;
            text += "f";
            // Appended piece by piece: GCC 12's -O3 warns (-Wrestrict, a false positive) on
            // " " + std::to_string(...).
            for (int c = 0; c < 3; ++c) {
                text += ' ';
                text += std::to_string(f.v[static_cast<std::size_t>(c)] + 1);
                text += "//";
                text += std::to_string(f.n[static_cast<std::size_t>(c)] + 1);
            }
            text += "\n";
        }
    }
    return text;
}

std::string mtlText(const Model& model)
{
    std::string text = "# " + model.name +
                       ": materials for OBJ viewers; the firmware takes them from "
                       "catalogue.toml. Generated by tools/overlaygen.\n";
    for (const Material& m : model.materials) {
        text += "newmtl " + m.name + "\n";
        text += "Ka 0.000 0.000 0.000\n";
        text += "Kd " + number(m.rgba[0], 3) + " " + number(m.rgba[1], 3) + " " +
                number(m.rgba[2], 3) + "\n";
        const double specular = m.shininess > 0.0 ? 0.5 : 0.0;
        text += "Ks " + number(specular, 3) + " " + number(specular, 3) + " " +
                number(specular, 3) + "\n";
        text += "Ns " + number(m.shininess, 1) + "\n";
        text += "d " + number(m.rgba[3], 3) + "\n";
        text += "illum 2\n";
    }
    return text;
}

std::string catalogueEntry(const Model& model)
{
    std::string text = "\n# " + model.description + "\n";
    text += "[[overlay]]\n";
    text += "name = \"" + model.name + "\"\n";
    text += "kind = \"" + model.kind + "\"\n";
    text += "anchor = \"" + model.anchor + "\"\n";
    text += "measure = \"" + model.measure + "\"\n";
    const double metres = model.measure == "interocular" ? 0.063 : 0.15;
    text += "scale = " + number(model.scale, 6) + "  # the OBJ is in metres: 1 m / " +
            number(metres, 3) + " m\n";
    const auto& r = model.rotationDegrees;
    if (r[0] != 0.0 || r[1] != 0.0 || r[2] != 0.0)
        text += "rotation = [" + number(r[0], 1) + ", " + number(r[1], 1) + ", " + number(r[2], 1) +
                "]\n";
    for (std::size_t m = 0; m < model.materials.size(); ++m) {
        const Material& material = model.materials[m];
        std::string objects;
        for (const Part& p : model.parts)
            if (p.material == static_cast<int>(m))
                objects += (objects.empty() ? "\"" : ", \"") + p.name + "\"";
        if (objects.empty())
            continue;
        text += "\n  [[overlay.mesh]]  # " + material.name + "\n";
        text += "  obj = \"" + objPath(model) + "\"\n";
        text += "  objects = [" + objects + "]\n";
        text += "  color = [" + number(material.rgba[0], 3) + ", " + number(material.rgba[1], 3) +
                ", " + number(material.rgba[2], 3) + ", " + number(material.rgba[3], 3) + "]\n";
        text += "  shininess = " + number(material.shininess, 1) + "\n";
    }
    const auto vector = [](const std::array<double, 3>& v, int digits) {
        std::string out = "[";
        for (std::size_t i = 0; i < v.size(); ++i) {
            out += number(v[i], digits);
            out += i + 1 < v.size() ? ", " : "]";
        }
        return out;
    };
    for (const Follow& f : model.follows) {
        text += "\n  [[overlay.follow]]  # per unit of the fitted animation value\n";
        text += "  unit = \"" + f.unit + "\"\n";
        if (f.offset != std::array<double, 3>{})
            text += "  offset = " + vector(f.offset, 4) + "  # metres of the OBJ\n";
        if (f.rotationDegrees != std::array<double, 3>{})
            text += "  rotation = " + vector(f.rotationDegrees, 1) + "\n";
        if (f.stretch != std::array<double, 3>{})
            text += "  stretch = " + vector(f.stretch, 3) + "\n";
    }
    return text;
}

namespace {
constexpr const char* kBegin =
    "# BEGIN overlaygen: generated by tools/overlaygen (cmake --build <build> --target\n"
    "# overlay-assets); change the generator, not this block.\n";
constexpr const char* kEnd = "# END overlaygen\n";
}  // namespace

std::string catalogueBlock(const std::vector<Model>& models)
{
    std::string text = kBegin;
    for (const Model& model : models)
        text += catalogueEntry(model);
    text += kEnd;
    return text;
}

std::string mergeCatalogue(const std::string& existing, const std::string& block)
{
    const std::size_t begin = existing.find(kBegin);
    const std::size_t end = existing.find(kEnd);
    if (begin != std::string::npos && end != std::string::npos && end > begin)
        return existing.substr(0, begin) + block + existing.substr(end + std::strlen(kEnd));
    return "# The mirror's overlays (format: FORMAT.md). Hand-made overlays go below the\n"
           "# generated block.\n"
           "version = 1\n\n" +
           block;
}

}  // namespace overlaygen
