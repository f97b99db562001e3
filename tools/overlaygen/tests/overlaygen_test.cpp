// overlaygen: the generated models are valid OBJ for tinyobjloader (the firmware's loader),
// watertight and outward-wound, with unit normals, deterministic, sized for the catalogue's
// head, and identical to the files committed in assets/overlays/.

#include "asset_files.hpp"
#include "models.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>
#include <toml++/toml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <set>

namespace {

using overlaygen::Model;
using overlaygen::Vec3;

std::string overlayDir()
{
    return testing_support::sourceDir() + "/assets/overlays";
}

struct LoadedObj {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
};

LoadedObj load(const Model& model)
{
    LoadedObj obj;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    const std::string path = overlayDir() + "/" + overlaygen::objPath(model);
    const std::string base = overlayDir() + "/" + model.name + "/";
    const bool ok = tinyobj::LoadObj(&obj.attrib, &obj.shapes, &materials, &warning, &error,
                                     path.c_str(), base.c_str(), true);
    EXPECT_TRUE(ok) << path << ": " << error;
    EXPECT_TRUE(error.empty()) << path << ": " << error;
    EXPECT_TRUE(warning.empty()) << path << ": " << warning;
    // The .mtl is for other viewers; it names the same materials as the catalogue.
    EXPECT_EQ(materials.size(), model.materials.size()) << path;
    return obj;
}

Vec3 vertex(const LoadedObj& obj, int index)
{
    const std::size_t i = static_cast<std::size_t>(index) * 3;
    return Vec3(obj.attrib.vertices[i], obj.attrib.vertices[i + 1], obj.attrib.vertices[i + 2]);
}

Vec3 normal(const LoadedObj& obj, int index)
{
    const std::size_t i = static_cast<std::size_t>(index) * 3;
    return Vec3(obj.attrib.normals[i], obj.attrib.normals[i + 1], obj.attrib.normals[i + 2]);
}

/// Metres in the head frame (eye midpoint origin) of a model-frame point.
Vec3 onHead(const Model& model, const Vec3& p)
{
    if (model.anchor == "head_top")
        return p + Vec3(overlaygen::HeadMetrics::headTop[0], overlaygen::HeadMetrics::headTop[1],
                        overlaygen::HeadMetrics::headTop[2]);
    return p;
}

/// > 1 outside the renderer's head proxy, < 1 inside (head frame, metres): an ellipsoid with
/// superelliptic horizontal sections.
double insideProxy(const Vec3& p)
{
    using overlaygen::HeadMetrics;
    double d[3];
    for (int k = 0; k < 3; ++k)
        d[k] = (p[k] - HeadMetrics::proxyCentre[k]) / HeadMetrics::proxySemiAxes[k];
    const double section = std::pow(std::pow(std::abs(d[0]), HeadMetrics::proxySquareness) +
                                        std::pow(std::abs(d[2]), HeadMetrics::proxySquareness),
                                    1.0 / HeadMetrics::proxySquareness);
    return section * section + d[1] * d[1];
}

class EveryModel : public ::testing::TestWithParam<int> {
protected:
    static const std::vector<Model>& models()
    {
        static const std::vector<Model> all = overlaygen::buildAllModels();
        return all;
    }
    const Model& model() const { return models()[static_cast<std::size_t>(GetParam())]; }
};

TEST(Overlaygen, GenerationIsDeterministic)
{
    const auto first = overlaygen::meshFiles(overlaygen::buildAllModels());
    const auto second = overlaygen::meshFiles(overlaygen::buildAllModels());
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t k = 0; k < first.size(); ++k) {
        EXPECT_EQ(first[k].path, second[k].path);
        EXPECT_TRUE(first[k].text == second[k].text) << first[k].path;
    }
    EXPECT_EQ(overlaygen::catalogueBlock(overlaygen::buildAllModels()),
              overlaygen::catalogueBlock(overlaygen::buildAllModels()));
}

TEST(Overlaygen, CommittedAssetsAreTheGeneratorsOutput)
{
    const auto stale = overlaygen::staleAssets(overlayDir(), overlaygen::buildAllModels());
    for (const std::string& line : stale)
        ADD_FAILURE() << line << " (rebuild the overlay-assets target)";
}

TEST(Overlaygen, CatalogueMergeKeepsHandWrittenOverlays)
{
    const std::string block = overlaygen::catalogueBlock(overlaygen::buildAllModels());
    const std::string fresh = overlaygen::mergeCatalogue("", block);
    const std::string mine = fresh + "\n[[overlay]]\nname = \"mine\"\n";
    const std::string merged = overlaygen::mergeCatalogue(mine, block);
    EXPECT_EQ(merged, mine);
}

TEST(Overlaygen, CatalogueIsValidTomlNamingEveryModelsObjects)
{
    const toml::table catalogue = toml::parse_file(overlayDir() + "/catalogue.toml");
    EXPECT_EQ(catalogue["version"].value_or(0), 1);
    const toml::array* overlays = catalogue["overlay"].as_array();
    ASSERT_NE(overlays, nullptr);
    std::map<std::string, const toml::table*> byName;
    for (const toml::node& node : *overlays)
        byName[node.as_table()->at("name").value_or(std::string())] = node.as_table();
    for (const Model& model : overlaygen::buildAllModels()) {
        ASSERT_TRUE(byName.contains(model.name)) << model.name;
        const toml::table& entry = *byName[model.name];
        EXPECT_EQ(entry["kind"].value_or(std::string()), model.kind);
        EXPECT_EQ(entry["anchor"].value_or(std::string()), model.anchor);
        // Every part is drawn by exactly one mesh entry.
        std::multiset<std::string> drawn;
        for (const toml::node& mesh : *entry["mesh"].as_array()) {
            EXPECT_EQ(mesh.as_table()->at("obj").value_or(std::string()),
                      overlaygen::objPath(model));
            for (const toml::node& object : *mesh.as_table()->at("objects").as_array())
                drawn.insert(object.value_or(std::string()));
            EXPECT_EQ(mesh.as_table()->at("color").as_array()->size(), 4u);
        }
        std::multiset<std::string> parts;
        for (const overlaygen::Part& part : model.parts)
            parts.insert(part.name);
        EXPECT_EQ(drawn, parts) << model.name;
    }
}

TEST_P(EveryModel, LoadsWithUnitNormalsAndNoDegenerateTriangles)
{
    const LoadedObj obj = load(model());
    std::set<std::string> names;
    std::size_t triangles = 0;
    for (const tinyobj::shape_t& shape : obj.shapes) {
        names.insert(shape.name);
        triangles += shape.mesh.indices.size() / 3;
        for (const tinyobj::index_t& index : shape.mesh.indices)
            ASSERT_GE(index.normal_index, 0) << shape.name;
        for (std::size_t f = 0; f + 2 < shape.mesh.indices.size(); f += 3) {
            const Vec3 a = vertex(obj, shape.mesh.indices[f].vertex_index);
            const Vec3 b = vertex(obj, shape.mesh.indices[f + 1].vertex_index);
            const Vec3 c = vertex(obj, shape.mesh.indices[f + 2].vertex_index);
            const Vec3 faceNormal = (b - a).cross(c - a);
            ASSERT_GT(faceNormal.norm(), 1e-13) << shape.name << " face " << f / 3;
            // The winding agrees with the normals: counter-clockwise seen from outside.
            const Vec3 corners = normal(obj, shape.mesh.indices[f].normal_index) +
                                 normal(obj, shape.mesh.indices[f + 1].normal_index) +
                                 normal(obj, shape.mesh.indices[f + 2].normal_index);
            EXPECT_GT(corners.dot(faceNormal), 0.0) << shape.name << " face " << f / 3;
        }
    }
    for (std::size_t n = 0; n < obj.attrib.normals.size() / 3; ++n)
        EXPECT_NEAR(normal(obj, static_cast<int>(n)).norm(), 1.0, 1e-3);
    std::set<std::string> parts;
    for (const overlaygen::Part& part : model().parts)
        parts.insert(part.name);
    EXPECT_EQ(names, parts);
    // The catalogue format's budget (FORMAT.md): ~1500 per overlay, glasses ~800, because
    // software GL pays per triangle and three faces must cost at most 2 ms a frame.
    EXPECT_LE(triangles, model().kind == "glasses" ? 900u : 1500u) << "budget of FORMAT.md";
    EXPECT_GT(triangles, 500u);
}

TEST_P(EveryModel, EveryPartIsWatertightAndFacesOutwards)
{
    const LoadedObj obj = load(model());
    std::map<std::string, std::string> groupOf;
    for (const overlaygen::Part& part : model().parts)
        groupOf[part.name] = part.closureGroup;
    // Per closure group: each directed edge a->b is matched by b->a (a closed, consistently
    // oriented surface, or a union of them), and the enclosed volume is positive (outwards).
    std::map<std::string, std::map<std::pair<int, int>, int>> edges;
    std::map<std::string, double> volume;
    for (const tinyobj::shape_t& shape : obj.shapes) {
        const std::string& group = groupOf[shape.name];
        for (std::size_t f = 0; f + 2 < shape.mesh.indices.size(); f += 3) {
            int v[3];
            for (int c = 0; c < 3; ++c)
                v[c] = shape.mesh.indices[f + static_cast<std::size_t>(c)].vertex_index;
            for (int c = 0; c < 3; ++c)
                ++edges[group][{v[c], v[(c + 1) % 3]}];
            volume[group] += vertex(obj, v[0]).dot(vertex(obj, v[1]).cross(vertex(obj, v[2]))) / 6;
        }
    }
    for (const auto& [group, directed] : edges) {
        int open = 0;
        for (const auto& [edge, count] : directed) {
            const auto reverse = directed.find({edge.second, edge.first});
            if (reverse == directed.end() || reverse->second != count)
                ++open;
        }
        EXPECT_EQ(open, 0) << model().name << " " << group;
        EXPECT_GT(volume[group], 0.0) << model().name << " " << group;
    }
}

TEST_P(EveryModel, FitsTheCataloguesHead)
{
    const LoadedObj obj = load(model());
    Eigen::AlignedBox3d box;
    for (std::size_t v = 0; v < obj.attrib.vertices.size() / 3; ++v)
        box.extend(onHead(model(), vertex(obj, static_cast<int>(v))));
    const Vec3 proxyTop(
        0.0, overlaygen::HeadMetrics::proxyCentre[1] + overlaygen::HeadMetrics::proxySemiAxes[1],
        overlaygen::HeadMetrics::proxyCentre[2]);
    if (model().kind == "glasses") {
        // Front in front of the eyes, arms back to the ears just outside the head.
        EXPECT_GT(box.max().z(), 0.012);
        EXPECT_LT(box.min().z(), -0.10);
        EXPECT_GT(box.sizes().x(), 0.155);
        EXPECT_LT(box.sizes().x(), 0.175);
        // Between the hinges and the ears the arms run just outside the head proxy, so the head
        // hides only the far arm.
        for (std::size_t v = 0; v < obj.attrib.vertices.size() / 3; ++v) {
            const Vec3 p = vertex(obj, static_cast<int>(v));
            if (p.z() < -0.03 && p.z() > -0.10) {
                EXPECT_GT(insideProxy(p), 1.0) << "temple inside the head proxy at " << p.z();
            }
        }
    } else {
        // Every hat covers the top of the head.
        EXPECT_GT(box.max().y(), proxyTop.y());
        EXPECT_LT(box.min().y(), proxyTop.y());
        EXPECT_TRUE(box.contains(Vec3(0.0, box.center().y(), proxyTop.z())));
        if (model().name != "party_hat") {
            // Worn on the head, not perched on it: the opening fits a 0.57 m head (the proxy is
            // smaller) and sits on the forehead.
            EXPECT_GT(box.sizes().x(), 0.165);
            EXPECT_GT(box.sizes().z(), 0.205);
            EXPECT_LT(box.min().y(), 0.07);
        }
    }
}

/// The hats and glasses (the face hair, kind "other", sits on the face, not over the head).
std::vector<int> hatsAndGlasses()
{
    std::vector<int> indices;
    const std::vector<Model> all = overlaygen::buildAllModels();
    for (std::size_t k = 0; k < all.size(); ++k)
        if (all[k].kind != "other")
            indices.push_back(static_cast<int>(k));
    return indices;
}

INSTANTIATE_TEST_SUITE_P(
    Models, EveryModel, ::testing::ValuesIn(hatsAndGlasses()),
    [](const ::testing::TestParamInfo<int>& param) {
        return overlaygen::buildAllModels()[static_cast<std::size_t>(param.param)].name;
    });

}  // namespace
