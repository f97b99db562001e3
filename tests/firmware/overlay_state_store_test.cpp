#include "firmware/overlay_state_store.hpp"

#include "alloc_counter.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using firmware::OverlayMode;
using firmware::OverlayStateStore;

std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(OverlayStateStore, SavesAndLoadsTheSelection)
{
    const std::string dir = testing_support::freshOutputDir("overlay_store") + "/nested/state";
    OverlayStateStore store(dir);
    ASSERT_TRUE(store.usable()) << store.lastError();
    EXPECT_EQ(store.path(), dir + "/overlay.toml");
    std::string warning;
    EXPECT_FALSE(store.load(warning).has_value());
    EXPECT_TRUE(warning.empty());

    ASSERT_TRUE(store.save("top-hat", OverlayMode::PerFace)) << store.lastError();
    EXPECT_FALSE(fs::exists(store.path() + ".tmp"));
    const auto loaded = OverlayStateStore(dir).load(warning);
    ASSERT_TRUE(loaded.has_value()) << warning;
    EXPECT_EQ(loaded->overlay, "top-hat");
    EXPECT_EQ(loaded->mode, OverlayMode::PerFace);

    // Overwritten in place.
    ASSERT_TRUE(store.save("none", OverlayMode::Global));
    const auto again = store.load(warning);
    ASSERT_TRUE(again.has_value()) << warning;
    EXPECT_EQ(again->overlay, "none");
    EXPECT_EQ(again->mode, OverlayMode::Global);
}

TEST(OverlayStateStore, SavesFromASelection)
{
    const std::string dir = testing_support::freshOutputDir("overlay_store_selection");
    firmware::OverlaySelection selection({"glasses", "sun-hat"}, {}, 1);
    OverlayStateStore store(dir);
    ASSERT_TRUE(store.save(selection));
    std::string warning;
    const auto loaded = store.load(warning);
    ASSERT_TRUE(loaded.has_value()) << warning;
    EXPECT_EQ(loaded->overlay, "sun-hat");
    firmware::OverlaySelection restored({"glasses", "sun-hat"}, {});
    EXPECT_TRUE(restored.select(loaded->overlay));
    EXPECT_EQ(restored.selected(), 1);
}

TEST(OverlayStateStore, NamesWithQuotesAndUnicodeSurvive)
{
    OverlayStateStore store(testing_support::freshOutputDir("overlay_store_names"));
    const std::string name = "chapeau \"élégant\" \\ 2";
    ASSERT_TRUE(store.save(name, OverlayMode::Global)) << store.lastError();
    std::string warning;
    const auto loaded = store.load(warning);
    ASSERT_TRUE(loaded.has_value()) << warning;
    EXPECT_EQ(loaded->overlay, name);
    EXPECT_FALSE(store.save("tab\there", OverlayMode::Global));
    EXPECT_FALSE(
        store.save(std::string(OverlayStateStore::kMaxNameLength + 1, 'x'), OverlayMode::Global));
    EXPECT_FALSE(store.save("", OverlayMode::Global));
    // A refused save leaves the file as it was.
    const auto still = store.load(warning);
    ASSERT_TRUE(still.has_value());
    EXPECT_EQ(still->overlay, name);
}

TEST(OverlayStateStore, CorruptOrForeignFilesAreIgnoredWithAWarning)
{
    const std::string dir = testing_support::freshOutputDir("overlay_store_corrupt");
    OverlayStateStore store(dir);
    const char* bad[] = {
        "overlay = \"top-hat\n",                         // unterminated string
        "overlay = \"top-hat\"\n",                       // no mode
        "overlay = \"top-hat\"\nmode = \"sideways\"\n",  // unknown mode
        "overlay = 3\nmode = \"global\"\n",              // wrong type
        "overlay = \"\"\nmode = \"global\"\n",           // empty name
        "\x89PNG\r\n\x1a\n",                             // not text
        "",                                              // empty (a crash mid-write elsewhere)
    };
    for (const char* text : bad) {
        std::ofstream(store.path(), std::ios::binary) << text;
        std::string warning;
        EXPECT_FALSE(store.load(warning).has_value()) << text;
        EXPECT_NE(warning.find("overlay.toml"), std::string::npos) << warning;
        EXPECT_NE(warning.find("ignored"), std::string::npos) << warning;
        EXPECT_EQ(warning.find('\n'), std::string::npos) << "one line: " << warning;
        EXPECT_EQ(readFile(store.path()), text) << "a corrupt file is left for inspection";
    }
    // And a good save replaces it.
    ASSERT_TRUE(store.save("glasses", OverlayMode::Global));
    std::string warning;
    EXPECT_TRUE(store.load(warning).has_value()) << warning;
}

TEST(OverlayStateStore, AFifoInPlaceOfTheFileIsIgnoredWithoutWaitingForAWriter)
{
    const std::string dir = testing_support::freshOutputDir("overlay_store_fifo");
    OverlayStateStore store(dir);
    ASSERT_EQ(::mkfifo(store.path().c_str(), 0600), 0);
    std::string warning;
    EXPECT_FALSE(store.load(warning).has_value());
    EXPECT_EQ(warning,
              store.path() + ": not a regular file (a FIFO, a device or a socket); ignored");
}

TEST(OverlayStateStore, AFolderThatCannotBeMadeIsReportedNotThrown)
{
    OverlayStateStore store("/proc/mirror-state");
    EXPECT_FALSE(store.usable());
    EXPECT_NE(std::string(store.lastError()).find("/proc/mirror-state"), std::string::npos);
    EXPECT_FALSE(store.save("glasses", OverlayMode::Global));
}

TEST(OverlayStateStore, AnUnwritableFileIsAFailureWithAReason)
{
    const std::string dir = testing_support::freshOutputDir("overlay_store_unwritable");
    OverlayStateStore store(dir);
    // A folder where the temp file should go: open() fails whoever runs the test (root too).
    fs::create_directory(store.path() + ".tmp");
    EXPECT_FALSE(store.save("glasses", OverlayMode::Global));
    EXPECT_NE(std::string(store.lastError()).find("overlay.toml.tmp"), std::string::npos)
        << store.lastError();
}

TEST(OverlayStateStore, SavingDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    OverlayStateStore store(testing_support::freshOutputDir("overlay_store_alloc"));
    ASSERT_TRUE(store.save("top-hat", OverlayMode::Global));
    testing_support::AllocationScope scope;
    ASSERT_TRUE(store.save("party-hat", OverlayMode::PerFace));
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

}  // namespace
