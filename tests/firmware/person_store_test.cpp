// PersonStore: a person's file keeps only their signature's numbers, their overlay and birthday;
// it comes back as it was written (mode 0600); a corrupt, unreadable or another model's file is
// skipped with one warning naming it; names are a safe charset and length.
#include "firmware/person_store.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

firmware::Person person(const char* name, float value)
{
    firmware::Person p;
    firmware::copyName(name, p.name, sizeof p.name);
    p.signature.shapeUnits.fill(value);
    p.signature.appearanceCount = 3;
    p.signature.appearance[0] = -value;
    p.signature.appearance[2] = 1e-7f;
    p.signature.textureCount = vision::kFaceSignatureMaxTexture;
    for (int i = 0; i < p.signature.textureCount; ++i)
        p.signature.texture[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i * 7 + 1);
    p.signature.samples = 24;
    return p;
}

TEST(PersonStore, NamesAreASafeCharsetAndLength)
{
    const char* why = "";
    for (const char* good : {"anna", "Bob_2", "guest-1", "0", "abcdefghijklmnopqrstuvwxyz012345"})
        EXPECT_TRUE(firmware::checkPersonName(good, why)) << good;
    for (const char* bad : {"", "../x", "a/b", "a b", "-a", "_a", ".hidden", "guest", "anna.toml",
                            "abcdefghijklmnopqrstuvwxyz0123456", "\xc3\xa9"}) {
        why = "";
        EXPECT_FALSE(firmware::checkPersonName(bad, why)) << bad;
        EXPECT_STRNE(why, "") << bad;
    }
    int m = 0, d = 0;
    EXPECT_TRUE(firmware::parseBirthday("02-29", m, d));
    EXPECT_EQ(m * 100 + d, 229);
    for (const char* bad : {"2-29", "13-01", "04-31", "00-10", "02-30", "0a-01", "03-14x"})
        EXPECT_FALSE(firmware::parseBirthday(bad, m, d)) << bad;
}

TEST(PersonStore, APersonComesBackAsWrittenAndTheFileIsTheServicesAlone)
{
    const std::string state = testing_support::freshOutputDir("person_store_roundtrip");
    firmware::PersonStore store(state, 0x1234abcd);
    ASSERT_TRUE(store.usable()) << store.lastError();
    firmware::Person anna = person("anna", 0.125f);
    firmware::copyName("top_hat", anna.overlay, sizeof anna.overlay);
    anna.birthdayMonth = 3;
    anna.birthdayDay = 14;
    ASSERT_TRUE(store.save(anna)) << store.lastError();
    ASSERT_TRUE(store.save(person("bob", -0.5f))) << store.lastError();
    struct stat st {};
    ASSERT_EQ(::stat((state + "/people/anna.toml").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);

    std::vector<std::string> warnings;
    const std::vector<firmware::Person> people = store.loadAll(warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_EQ(people.size(), 2u);
    EXPECT_STREQ(people[0].name, "anna");
    EXPECT_EQ(people[0].signature.shapeUnits, anna.signature.shapeUnits);
    EXPECT_EQ(people[0].signature.appearanceCount, 3);
    EXPECT_EQ(people[0].signature.appearance, anna.signature.appearance) << "bit for bit";
    EXPECT_EQ(people[0].signature.textureCount, vision::kFaceSignatureMaxTexture);
    EXPECT_EQ(people[0].signature.texture, anna.signature.texture);
    EXPECT_EQ(people[0].signature.samples, 24);
    EXPECT_STREQ(people[0].overlay, "top_hat");
    EXPECT_EQ(people[0].birthdayMonth * 100 + people[0].birthdayDay, 314);
    EXPECT_STREQ(people[1].name, "bob");
    EXPECT_STREQ(people[1].overlay, "");
    EXPECT_EQ(people[1].birthdayMonth, 0);

    ASSERT_TRUE(store.remove("bob"));
    ASSERT_TRUE(store.remove("bob")) << "gone already is fine";
    EXPECT_EQ(store.loadAll(warnings).size(), 1u);
}

TEST(PersonStore, CorruptUnreadableAndForeignFilesAreSkippedWithAWarningNamingThem)
{
    const std::string state = testing_support::freshOutputDir("person_store_skipped");
    firmware::PersonStore other(state, 0x11111111);
    ASSERT_TRUE(other.save(person("foreign", 0.1f)));
    firmware::PersonStore store(state, 0x22222222);
    ASSERT_TRUE(store.save(person("good", 0.2f)));
    const std::string dir = state + "/people/";
    std::ofstream(dir + "broken.toml") << "name = \"broken\"\nshape = [1, 2,\n";
    std::ofstream(dir + "short.toml") << "name = \"short\"\nmodel = \"crc32:22222222\"\n"
                                         "samples = 3\nshape = [1.0, 2.0]\n";
    std::ofstream(dir + "renamed.toml") << "name = \"someone\"\n";
    std::ofstream(dir + "texture.toml") << "name = \"texture\"\nmodel = \"crc32:22222222\"\n"
                                           "samples = 3\nshape = [0, 0, 0, 0, 0, 0, 0, 0, 0, 0]\n"
                                           "texture = \"0a1g\"\n";
    ASSERT_EQ(::mkfifo((dir + "fifo.toml").c_str(), 0600), 0) << "a FIFO: unreadable as a file";
    std::ofstream(dir + "notes.txt") << "not a person";

    std::vector<std::string> warnings;
    const std::vector<firmware::Person> people = store.loadAll(warnings);
    ASSERT_EQ(people.size(), 1u);
    EXPECT_STREQ(people[0].name, "good");
    ASSERT_EQ(warnings.size(), 6u);
    for (const char* name : {"broken", "short", "renamed", "texture", "fifo", "foreign"}) {
        bool named = false;
        for (const std::string& w : warnings)
            named = named || w.find(dir + name + ".toml") != std::string::npos;
        EXPECT_TRUE(named) << name;
    }
    for (const std::string& w : warnings) {
        EXPECT_EQ(w.find('\n'), std::string::npos) << w;
        EXPECT_EQ(w.rfind("people: ", 0), 0u) << w;
    }
    bool foreign = false;
    for (const std::string& w : warnings)
        foreign = foreign || w.find("another AAM model") != std::string::npos;
    EXPECT_TRUE(foreign);
    EXPECT_TRUE(std::filesystem::exists(dir + "foreign.toml")) << "skipped, not deleted";
}

}  // namespace
