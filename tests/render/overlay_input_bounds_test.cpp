// The overlay catalogue at its edges: files that are not regular files, OBJ values that are not
// finite or have no area, an overlay over the triangle budget, a PNG whose header claims a huge
// picture. Each is one line naming the file, refused before it costs memory or reaches GL.

#include "platform/png_writer.hpp"
#include "render/overlay_catalogue.hpp"
#include "test_paths.hpp"
#include "vision/input_limits.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using render::OverlayCatalogue;
using testing_support::freshOutputDir;

const char* const kCatalogue = R"(version = 1
[[overlay]]
name = "g"
kind = "glasses"
anchor = "eye_midpoint"
measure = "interocular"
  [[overlay.mesh]]
  obj = "mesh.obj"
)";

void writeFile(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

/// The error of loading a catalogue of one mesh, `obj`, in a fresh folder (with `extra` lines
/// appended to its mesh table); "" when it loads.
std::string loadError(const std::string& folder, const std::string& obj,
                      const std::string& extra = "")
{
    const std::string dir = freshOutputDir("overlay_input_bounds_" + folder);
    writeFile(dir + "/mesh.obj", obj);
    writeFile(dir + "/catalogue.toml", kCatalogue + extra);
    try {
        OverlayCatalogue::load(dir + "/catalogue.toml");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

const char* const kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";

TEST(OverlayInputBounds, ACatalogueThatIsNotARegularFileIsOneLine)
{
    const std::string fifo = freshOutputDir("overlay_fifo") + "/catalogue.toml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& path : {std::string("/dev/zero"), fifo}) {
        try {
            OverlayCatalogue::load(path);
            ADD_FAILURE() << "loaded " << path;
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "overlay catalogue " + path +
                                                 ": not a regular file (a FIFO, a device or a "
                                                 "socket)");
        }
    }
}

TEST(OverlayInputBounds, NonFiniteOrFarVerticesAreRefused)
{
    EXPECT_EQ(loadError("good", kTriangle), "");
    // tinyobjloader alone reads these as 0 (or 1e999 as infinity), without a word.
    for (const char* bad : {"nan", "inf", "-inf", "1e999", "abc", "0x10"}) {
        const std::string e =
            loadError("bad_number", std::string("v 0 0 0\nv ") + bad + " 0 0\nv 0 1 0\nf 1 2 3\n");
        EXPECT_NE(e.find("catalogue.toml:7: overlay 'g': OBJ mesh.obj:2: '" + std::string(bad) +
                         "' is not a finite number"),
                  std::string::npos)
            << bad << ": " << e;
    }
    const std::string far = loadError("far", "v 1e30 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(far.find("OBJ mesh.obj: vertex 1 has coordinate 1e+30 (allowed: finite, within "
                       "+-1000)"),
              std::string::npos)
        << far;
}

TEST(OverlayInputBounds, AMeshWithoutAreaIsRefused)
{
    // Identical vertices, and three on one line: nothing would ever be drawn.
    for (const char* obj : {"v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3\n",
                            "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\nf 3 2 1\n"}) {
        const std::string e = loadError("no_area", obj);
        EXPECT_NE(e.find("OBJ mesh.obj: no face has any area"), std::string::npos) << e;
    }
    // A flat quad is an open surface (a lens): drawn from both sides, accepted.
    EXPECT_EQ(loadError("quad", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n"), "");
}

TEST(OverlayInputBounds, AnOverlayOverTheTriangleBudgetIsRefused)
{
    const auto strip = [](int triangles) {
        std::string obj;
        for (int i = 0; i < triangles + 2; ++i)
            obj += "v " + std::to_string(i * 0.01) + " " + std::to_string(i % 2) + " 0\n";
        for (int i = 1; i <= triangles; ++i)
            obj += "f " + std::to_string(i) + " " + std::to_string(i + 1) + " " +
                   std::to_string(i + 2) + "\n";
        return obj;
    };
    const int budget = vision::limits::kMaxOverlayTriangles;
    EXPECT_EQ(loadError("budget", strip(budget)), "");
    // Two meshes within the budget each, over it together.
    const std::string e = loadError("over_budget", strip(budget / 2 + 1),
                                    "  [[overlay.mesh]]\n  obj = \"mesh.obj\"\n");
    EXPECT_NE(e.find(std::to_string(budget + 2) + " triangles, over the budget of " +
                     std::to_string(budget) + " per overlay"),
              std::string::npos)
        << e;
}

TEST(OverlayInputBounds, AMeshOverTheBudgetIsRefusedWhileItIsRead)
{
    // 200,000 triangles of one repeated face: refused by the OBJ reader at the first triangle
    // over the budget, not after all of them are made into vertices and indexed.
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < 200000; ++i)
        obj += "f 1 2 3\n";
    const std::string e = loadError("mesh_over_budget", obj);
    EXPECT_NE(
        e.find("OBJ mesh.obj: more than " + std::to_string(vision::limits::kMaxOverlayTriangles) +
               " triangles, the budget of one overlay"),
        std::string::npos)
        << e;
}

std::uint32_t crc32(const std::uint8_t* data, std::size_t size)
{
    std::uint32_t crc = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void putBigEndian(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t value)
{
    for (int i = 0; i < 4; ++i)
        bytes[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(value >> (24 - 8 * i));
}

TEST(OverlayInputBounds, ATextureHeaderClaimingAHugePictureIsRefusedBeforeDecoding)
{
    const std::string dir = freshOutputDir("overlay_input_bounds_png");
    const std::vector<std::uint8_t> pixels(4 * 4 * 3, 200);
    platform::PngWriter writer;
    ASSERT_TRUE(writer.write((dir + "/small.png").c_str(), pixels.data(), 4, 4, 12))
        << writer.lastError();
    // The same file claiming 60000 x 60000 pixels (14 GB as RGBA), its IHDR checksum fixed.
    std::ifstream in(dir + "/small.png", std::ios::binary);
    std::vector<std::uint8_t> png((std::istreambuf_iterator<char>(in)), {});
    ASSERT_GT(png.size(), 33u);
    putBigEndian(png, 16, 60000);  // IHDR data starts at 16: width, height
    putBigEndian(png, 20, 60000);
    putBigEndian(png, 29, crc32(png.data() + 12, 17));  // over "IHDR" and its 13 data bytes
    std::ofstream(dir + "/bomb.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));

    const std::string e =
        loadError("png_bomb", kTriangle, "  texture = \"" + dir + "/bomb.png\"\n");
    EXPECT_NE(e.find("texture " + dir + "/bomb.png: 60000x60000 is larger than 4096x4096"),
              std::string::npos)
        << e;
    EXPECT_EQ(loadError("png_small", kTriangle, "  texture = \"" + dir + "/small.png\"\n"), "");
}

}  // namespace
