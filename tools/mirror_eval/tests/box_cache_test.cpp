// BoxCache (`mirror-eval aam --boxes`): the boxes and the frames without one come back as they
// were put; a malformed file is one error naming its line.

#include "box_cache.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace {

namespace fs = std::filesystem;

fs::path scratchFile(const std::string& name)
{
    const fs::path dir = fs::temp_directory_path() / "mirror_box_cache_test";
    fs::create_directories(dir);
    const fs::path p = dir / name;
    fs::remove(p);
    return p;
}

TEST(BoxCache, BoxesAndFramesWithoutOneComeBackAsTheyWerePut)
{
    const fs::path p = scratchFile("round.txt");
    {
        mirror_eval::BoxCache cache(p.string());
        EXPECT_FALSE(cache.find("f0").has_value()) << "a new file knows no frame";
        cache.put("f0", mirror_eval::FaceBoxPx{10.5, 20.25, 110.5, 130.75});
        cache.put("f1", std::nullopt);
        cache.save();
    }
    const mirror_eval::BoxCache again(p.string());
    const auto f0 = again.find("f0");
    ASSERT_TRUE(f0.has_value() && f0->has_value());
    EXPECT_DOUBLE_EQ((*f0)->left, 10.5);
    EXPECT_DOUBLE_EQ((*f0)->top, 20.25);
    EXPECT_DOUBLE_EQ((*f0)->right, 110.5);
    EXPECT_DOUBLE_EQ((*f0)->bottom, 130.75);
    const auto f1 = again.find("f1");
    ASSERT_TRUE(f1.has_value());
    EXPECT_FALSE(f1->has_value()) << "kept: no box on that frame";
    EXPECT_FALSE(again.find("f2").has_value());
}

TEST(BoxCache, AMalformedLineIsOneErrorNamingIt)
{
    for (const std::string bad : {"f0 -\nf1 1 2 3\n", "f0 -\nf1 5 5 4 9\n", "f0\n"}) {
        const fs::path p = scratchFile("bad.txt");
        std::ofstream(p) << bad;
        try {
            mirror_eval::BoxCache cache(p.string());
            ADD_FAILURE() << "accepted: " << bad;
        } catch (const std::runtime_error& e) {
            const std::string line = bad == "f0\n" ? "line 1" : "line 2";
            EXPECT_NE(std::string(e.what()).find(line), std::string::npos) << e.what();
        }
    }
}

}  // namespace
