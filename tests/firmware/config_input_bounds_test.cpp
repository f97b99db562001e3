// What the config accepts at its edges: files that are not regular files, string values with
// control characters or of any length, a --set with a line break, serial rates termios does not
// name. Each problem is one short line; none blocks, none reaches the terminal raw.

#include "firmware/config.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>
#include <vector>

namespace {

using firmware::ConfigError;

/// Every problem line of loading `path` (or the defaults) with `sets`; a failure if none.
std::vector<std::string> problemsOf(const std::string& path, std::vector<std::string> sets = {})
{
    try {
        (void)firmware::loadConfig({path, !path.empty(), std::move(sets)});
    } catch (const ConfigError& error) {
        std::vector<std::string> lines;
        for (const auto& problem : error.problems())
            lines.push_back(problem.format());
        return lines;
    }
    ADD_FAILURE() << "no ConfigError thrown";
    return {};
}

void expectPrintableLine(const std::string& line)
{
    for (const char c : line)
        EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            << "raw control character in: " << line;
}

TEST(ConfigInputBounds, AFifoInPlaceOfTheConfigIsRefusedWithoutWaitingForAWriter)
{
    const std::string path = testing_support::freshOutputDir("config_fifo") + "/mirror.toml";
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    EXPECT_EQ(problemsOf(path),
              (std::vector<std::string>{path + ":1:1: config: not a regular file (a FIFO, a "
                                               "device or a socket)"}));
}

TEST(ConfigInputBounds, ADeviceInPlaceOfTheConfigIsRefused)
{
    EXPECT_EQ(problemsOf("/dev/zero"),
              (std::vector<std::string>{"/dev/zero:1:1: config: not a regular file (a FIFO, a "
                                        "device or a socket)"}));
}

TEST(ConfigInputBounds, ControlCharactersInAStringAreOneEscapedLine)
{
    // TOML escapes: the values hold a line break, an escape sequence, a tab.
    for (const char* value : {R"(1920x1080\n[source])", R"(\u001b[2J1920x1080)", R"(a\tb)"}) {
        const auto lines = problemsOf("", {std::string("display.mode=\"") + value + "\""});
        ASSERT_EQ(lines.size(), 1u) << value;
        expectPrintableLine(lines[0]);
    }
    const auto esc = problemsOf("", {"display.mode=\"\\u001b[2J\""});
    ASSERT_EQ(esc.size(), 1u);
    EXPECT_EQ(esc[0],
              R"(--set:1:14: display.mode: control character 0x1B at byte 1 of "\u001B[2J" )"
              R"((allowed: "" or "preferred" (the panel's own), "WxH" or "WxH@Hz", e.g. )"
              R"("1280x720@60"))");
}

TEST(ConfigInputBounds, AHugeValueIsNamedByItsLengthNotEchoed)
{
    const std::string huge(900000, 'x');
    for (const std::string& set : {"display.mode=\"" + huge + "\"", "source.spec=\"" + huge + "\"",
                                   "log.level=\"" + huge + "\"", "display." + huge + "=1", huge}) {
        const auto lines = problemsOf("", {set});
        ASSERT_EQ(lines.size(), 1u);
        EXPECT_LT(lines[0].size(), 400u) << lines[0].substr(0, 400);
    }
    // The longest string a key takes is 4096 bytes (PATH_MAX).
    EXPECT_NO_THROW(
        firmware::loadConfig({"", false, {"faces.cascade=\"/" + std::string(4095, 'c') + "\""}}));
    const auto tooLong = problemsOf("", {"faces.cascade=\"/" + std::string(4096, 'c') + "\""});
    ASSERT_EQ(tooLong.size(), 1u);
    EXPECT_NE(tooLong[0].find("4097 bytes is too long (at most 4096)"), std::string::npos)
        << tooLong[0];
}

TEST(ConfigInputBounds, ASetWithALineBreakSetsNothing)
{
    const auto lines = problemsOf("", {"display.hud=false\nsource.spec=\"synthetic\""});
    EXPECT_EQ(lines, (std::vector<std::string>{
                         R"(--set:1:1: config: one key per --set, got a line break in )"
                         R"("display.hud=false\nsource.spec=\"synthetic\"" (allowed: KEY=VALUE )"
                         R"(on one line))"}));
}

TEST(ConfigInputBounds, OnlyTheSerialRatesTermiosNamesAreAccepted)
{
    EXPECT_EQ(firmware::loadConfig({"", false, {"console.baud=921600"}}).console.baud, 921600);
    for (const char* rate : {"12345", "115201", "1200", "4800", "4000001"}) {
        const auto lines = problemsOf("", {std::string("console.baud=") + rate});
        ASSERT_EQ(lines.size(), 1u);
        EXPECT_NE(lines[0].find("(allowed: 9600, 19200, 38400, 57600, 115200,"), std::string::npos)
            << lines[0];
    }
}

}  // namespace
