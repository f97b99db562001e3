#include "firmware/card_model_store.hpp"

#include "alloc_counter.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;

vision::CardColorModel sampleModel()
{
    vision::CardColorModel m;
    m.mean[0] = 92.125f;
    m.mean[1] = 121.5f;
    m.mean[2] = 41.375f;
    m.sigma[0] = 3.25f;
    m.sigma[1] = 2.875f;
    m.sigma[2] = 2.5f;
    m.valid = true;
    return m;
}

TEST(CardModelStore, SavesAndLoadsTheSameModel)
{
    const std::string dir = testing_support::freshOutputDir("card_store") + "/nested/state";
    firmware::CardModelStore store(dir);
    ASSERT_TRUE(store.usable()) << store.lastError();
    std::string warning;
    EXPECT_FALSE(store.load(warning).has_value());
    EXPECT_TRUE(warning.empty());

    ASSERT_TRUE(store.save(sampleModel())) << store.lastError();
    EXPECT_FALSE(fs::exists(store.path() + ".tmp"));
    const auto loaded = firmware::CardModelStore(dir).load(warning);
    ASSERT_TRUE(loaded.has_value()) << warning;
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(loaded->mean[i], sampleModel().mean[i], 1e-3);
        EXPECT_NEAR(loaded->sigma[i], sampleModel().sigma[i], 1e-3);
    }
    EXPECT_TRUE(loaded->valid);
}

TEST(CardModelStore, CorruptOrForeignFilesAreIgnoredWithAWarning)
{
    const std::string dir = testing_support::freshOutputDir("card_store_corrupt");
    firmware::CardModelStore store(dir);
    const char* bad[] = {"mean = [1, 2\n", "mean = [1, 2, 3]\n",
                         "mean = [1, 2, 3]\nsigma = [1, 2, 999]\n", "\x89PNG\r\n\x1a\n",
                         "mean = [nan, 1, 1]\nsigma = [1, 1, 1]\n",
                         "mean = [1, 2, 3]\nsigma = [0, 2, 2]\n",
                         "mean = [1, 2, 3]\nsigma = [0.5, 2, 2]\n"};
    for (const char* text : bad) {
        std::ofstream(store.path(), std::ios::binary) << text;
        std::string warning;
        EXPECT_FALSE(store.load(warning).has_value()) << text;
        EXPECT_NE(warning.find("card-model.toml"), std::string::npos) << warning;
        EXPECT_NE(warning.find("ignored"), std::string::npos) << warning;
        EXPECT_EQ(warning.find('\n'), std::string::npos) << "one line: " << warning;
    }
}

TEST(CardModelStore, AFifoInPlaceOfTheFileIsIgnoredWithoutWaitingForAWriter)
{
    const std::string dir = testing_support::freshOutputDir("card_store_fifo");
    firmware::CardModelStore store(dir);
    ASSERT_EQ(::mkfifo(store.path().c_str(), 0600), 0);
    std::string warning;
    EXPECT_FALSE(store.load(warning).has_value());
    EXPECT_EQ(warning,
              store.path() + ": not a regular file (a FIFO, a device or a socket); ignored");
}

TEST(CardModelStore, AFolderThatCannotBeMadeIsReportedNotThrown)
{
    firmware::CardModelStore store("/proc/mirror-state");
    EXPECT_FALSE(store.usable());
    EXPECT_NE(std::string(store.lastError()).find("/proc/mirror-state"), std::string::npos);
    EXPECT_FALSE(store.save(sampleModel()));
}

TEST(CardModelStore, SavingDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    firmware::CardModelStore store(testing_support::freshOutputDir("card_store_alloc"));
    const vision::CardColorModel model = sampleModel();
    ASSERT_TRUE(store.save(model));
    testing_support::AllocationScope scope;
    ASSERT_TRUE(store.save(model));
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

}  // namespace
