#include "render/overlay_catalogue.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace {

using render::OverlayCatalogue;
using testing_support::freshOutputDir;
using testing_support::sourceDir;

std::string testCatalogue()
{
    return sourceDir() + "/tests/data/overlays/catalogue.toml";
}

void writeFile(const std::string& path, const std::string& text)
{
    std::ofstream(path) << text;
}

// The error line of loading `toml` as a catalogue in a fresh folder beside a copy of the test
// glasses; "" when it loads.
std::string loadError(const std::string& folder, const std::string& toml)
{
    const std::string dir = freshOutputDir("overlay_catalogue_" + folder);
    std::filesystem::copy_file(sourceDir() + "/tests/data/overlays/test_glasses.obj",
                               dir + "/glasses.obj");
    writeFile(dir + "/catalogue.toml", toml);
    try {
        OverlayCatalogue::load(dir + "/catalogue.toml");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

const char* const kGood = R"(version = 1
[[overlay]]
name = "g"
kind = "glasses"
anchor = "eye_midpoint"
measure = "interocular"
  [[overlay.mesh]]
  obj = "glasses.obj"
)";

TEST(OverlayCatalogue, LoadsTheTestCatalogueIntoTriangleLists)
{
    const OverlayCatalogue catalogue = OverlayCatalogue::load(testCatalogue());
    ASSERT_EQ(catalogue.size(), 2);
    EXPECT_EQ(catalogue.find("test_glasses"), 0);
    EXPECT_EQ(catalogue.find("test_hat"), 1);
    EXPECT_EQ(catalogue.find("nope"), -1);

    const render::Overlay& glasses = catalogue[0];
    EXPECT_EQ(glasses.kind, render::OverlayKind::Glasses);
    EXPECT_EQ(glasses.anchor, render::OverlayAnchor::EyeMidpoint);
    EXPECT_EQ(glasses.measure, render::HeadMeasure::Interocular);
    ASSERT_EQ(glasses.meshes.size(), 4u);
    // 9 boxes of 6 quads in the frame, 1 box per temple, 2 quads of lens: 2 triangles a quad.
    EXPECT_EQ(glasses.meshes[0].indices.size(), 9u * 6u * 2u * 3u);
    // One box: 6 faces of 4 corners (flat normals keep the faces' corners apart; rounding may
    // give a quad's two triangles slightly different normals): shared vertices, fewer than 36.
    EXPECT_EQ(glasses.meshes[1].indices.size(), 6u * 2u * 3u);
    EXPECT_GE(glasses.meshes[1].vertices.size(), 6u * 4u);
    EXPECT_LT(glasses.meshes[1].vertices.size(), 6u * 6u);
    EXPECT_EQ(glasses.meshes[1].source, "test_glasses.obj[temple_left]");
    EXPECT_EQ(glasses.meshes[3].indices.size(), 2u * 2u * 3u);
    EXPECT_GE(glasses.meshes[3].vertices.size(), 2u * 4u);
    EXPECT_FALSE(glasses.meshes[0].material.transparent());
    EXPECT_TRUE(glasses.meshes[3].material.transparent());
    EXPECT_FLOAT_EQ(glasses.meshes[3].material.shininess, 80.f);
    // The left temple lies at x < 0 and runs back (z < 0) from the front.
    for (const render::OverlayVertex& v : glasses.meshes[1].vertices) {
        EXPECT_LT(v.position[0], -1.2f);
        EXPECT_LE(v.position[2], 0.25f);
    }
    // Flat normals where the OBJ has none, unit length.
    for (const render::OverlayVertex& v : glasses.meshes[0].vertices)
        EXPECT_NEAR(std::hypot(v.normal[0], v.normal[1], v.normal[2]), 1.f, 1e-4f);

    const render::Overlay& hat = catalogue[1];
    EXPECT_EQ(hat.anchor, render::OverlayAnchor::HeadTop);
    EXPECT_EQ(hat.measure, render::HeadMeasure::FaceWidth);
    EXPECT_FLOAT_EQ(hat.offset[1], -0.4f);
    EXPECT_FLOAT_EQ(hat.scale, 1.f);
}

// Signed volume of a mesh (positive: wound counter-clockwise seen from outside).
double signedVolume(const render::OverlayMesh& mesh)
{
    double v = 0.0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const float* a = mesh.vertices[mesh.indices[t]].position;
        const float* b = mesh.vertices[mesh.indices[t + 1]].position;
        const float* c = mesh.vertices[mesh.indices[t + 2]].position;
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6.0;
}

TEST(OverlayCatalogue, ClosedMeshesAreTurnedOutwardAndCulledOpenOnesDrawnFromBothSides)
{
    const std::string dir = freshOutputDir("overlay_catalogue_closed");
    // A cube of side 2 wound clockwise seen from outside (inside out), and an open square.
    writeFile(dir + "/shapes.obj",
              "o cube\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
              "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
              "f 8 7 6 5\nf 3 4 1 2\nf 7 3 2 6\nf 4 8 5 1\nf 4 3 7 8\nf 5 6 2 1\n"
              "o square\nv 0 0 3\nv 1 0 3\nv 1 1 3\nv 0 1 3\nf 9 10 11 12\n");
    writeFile(dir + "/catalogue.toml",
              std::string(kGood).replace(std::string(kGood).find("glasses.obj"), 11, "shapes.obj") +
                  "  objects = [\"cube\"]\n"
                  "  [[overlay.mesh]]\n  obj = \"shapes.obj\"\n  objects = [\"square\"]\n"
                  "  [[overlay.mesh]]\n  obj = \"shapes.obj\"\n  objects = [\"cube\"]\n"
                  "  double_sided = true\n");
    const OverlayCatalogue catalogue = OverlayCatalogue::load(dir + "/catalogue.toml");
    const render::Overlay& shapes = catalogue[0];
    ASSERT_EQ(shapes.meshes.size(), 3u);
    EXPECT_FALSE(shapes.meshes[0].material.doubleSided);
    EXPECT_NEAR(signedVolume(shapes.meshes[0]), 8.0, 1e-6) << "turned outward";
    EXPECT_TRUE(shapes.meshes[1].material.doubleSided) << "open";
    EXPECT_TRUE(shapes.meshes[2].material.doubleSided) << "the catalogue says so";
    EXPECT_NEAR(signedVolume(shapes.meshes[2]), -8.0, 1e-6) << "left as the file has it";

    // The test models: the temple boxes are closed, the hat's crown (no bottom) is open.
    const OverlayCatalogue test = OverlayCatalogue::load(testCatalogue());
    EXPECT_FALSE(test[0].meshes[1].material.doubleSided);
    EXPECT_TRUE(test[1].meshes[0].material.doubleSided);
}

TEST(OverlayCatalogue, TheProjectCatalogueLoadsWhenPresent)
{
    const std::string path = sourceDir() + "/assets/overlays/catalogue.toml";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "no " << path;
    const OverlayCatalogue catalogue = OverlayCatalogue::load(path);
    EXPECT_GE(catalogue.size(), 1);
    for (const render::Overlay& overlay : catalogue.overlays()) {
        EXPECT_FALSE(overlay.meshes.empty()) << overlay.name;
        for (const render::OverlayMesh& mesh : overlay.meshes) {
            EXPECT_EQ(mesh.indices.size() % 3, 0u) << mesh.source;
            for (const std::uint16_t i : mesh.indices)
                ASSERT_LT(i, mesh.vertices.size()) << mesh.source;
        }
    }
}

TEST(OverlayCatalogue, AGoodMinimalCatalogueLoads)
{
    EXPECT_EQ(loadError("good", kGood), "");
}

TEST(OverlayCatalogue, ErrorsAreOneLineNamingFileLineAndWhy)
{
    std::string e = loadError(
        "anchor", std::string(kGood).replace(std::string(kGood).find("eye_midpoint"), 12, "crown"));
    EXPECT_NE(e.find("catalogue.toml:5: overlay 'g': anchor must be one of "
                     "eye_midpoint|nose_bridge|forehead_top|head_top|upper_lip|chin, not 'crown'"),
              std::string::npos)
        << e;
    EXPECT_EQ(e.find('\n'), std::string::npos);

    e = loadError("missing_obj", std::string(kGood) + "  [[overlay.mesh]]\n  obj = \"hat.obj\"\n");
    EXPECT_NE(e.find("catalogue.toml:9: overlay 'g': OBJ hat.obj: no such file"), std::string::npos)
        << e;

    e = loadError("syntax", "version = 1\n[[overlay]\n");
    EXPECT_NE(e.find("catalogue.toml:2: "), std::string::npos) << e;

    e = loadError("no_kind", std::string(kGood).replace(std::string(kGood).find("kind"), 17, ""));
    EXPECT_NE(e.find("overlay 'g': missing key 'kind'"), std::string::npos) << e;

    e = loadError("objects", std::string(kGood) + "  objects = [\"visor\"]\n");
    EXPECT_NE(e.find("OBJ glasses.obj has no object or group 'visor'"), std::string::npos) << e;

    e = loadError("color", std::string(kGood) + "  color = [1.0, 0.5]\n");
    EXPECT_NE(e.find("catalogue.toml:9: overlay 'g': color must be an array of 4 numbers"),
              std::string::npos)
        << e;

    e = loadError("unknown", std::string(kGood) + "  colour = [1.0, 0.5, 0.2, 1.0]\n");
    EXPECT_NE(e.find("unknown mesh key 'colour'"), std::string::npos) << e;

    e = loadError("texture", std::string(kGood) + "  texture = \"nope.png\"\n");
    EXPECT_NE(e.find("texture "), std::string::npos) << e;
    EXPECT_NE(e.find("nope.png"), std::string::npos) << e;

    e = loadError("version", "version = 2\n");
    EXPECT_NE(e.find("catalogue.toml:1: version must be 1"), std::string::npos) << e;

    e = loadError("twice", std::string(kGood) +
                               std::string(kGood).substr(std::string(kGood).find("[[overlay]]")));
    EXPECT_NE(e.find("a second overlay with this name"), std::string::npos) << e;
}

TEST(OverlayCatalogue, ABadObjIsOneLineWithWhatTinyObjLoaderSays)
{
    const std::string dir = freshOutputDir("overlay_catalogue_bad_obj");
    writeFile(dir + "/bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    writeFile(dir + "/catalogue.toml",
              std::string(kGood).replace(std::string(kGood).find("glasses.obj"), 11, "bad.obj"));
    try {
        OverlayCatalogue::load(dir + "/catalogue.toml");
        FAIL() << "loaded a bad OBJ";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("overlay 'g': OBJ bad.obj"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

}  // namespace
