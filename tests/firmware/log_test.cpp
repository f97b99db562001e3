// The log: the ring `log` reads, filtered by level, and the journal's priority prefixes.
#include "firmware/log.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <string>
#include <vector>

namespace {

std::vector<std::string> recent(int n, firmware::LogLevel atLeast)
{
    std::vector<std::string> lines;
    firmware::forEachRecentLogLine(
        n,
        [](const char* line, void* context) {
            static_cast<std::vector<std::string>*>(context)->push_back(line);
        },
        &lines, atLeast);
    return lines;
}

std::string readAll(int fd)
{
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;)
        text.append(buffer, static_cast<std::size_t>(n));
    return text;
}

/// Logs into a pipe for the test's duration.
struct CapturedLog {
    int fds[2] = {-1, -1};
    CapturedLog()
    {
        EXPECT_EQ(::pipe(fds), 0);
        firmware::setLogLevel(firmware::LogLevel::Debug);
        firmware::setLogFd(fds[1]);
    }
    std::string text()
    {
        ::close(fds[1]);
        fds[1] = -1;
        return readAll(fds[0]);
    }
    ~CapturedLog()
    {
        firmware::setLogFd(2);
        firmware::setLogLevel(firmware::LogLevel::Info);
        for (const int fd : fds)
            if (fd >= 0)
                ::close(fd);
    }
};

TEST(Log, TheRingIsFilteredByLevel)
{
    CapturedLog capture;
    MIRROR_LOG_ERROR("ring test: error one");
    for (int i = 0; i < 30; ++i)
        MIRROR_LOG_INFO("ring test: info %d", i);
    MIRROR_LOG_WARN("ring test: warning two");
    MIRROR_LOG_DEBUG("ring test: debug three");

    const auto warnings = recent(2, firmware::LogLevel::Warn);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_NE(warnings[0].find("] E ring test: error one\n"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[1].find("] W ring test: warning two\n"), std::string::npos) << warnings[1];
    const auto errors = recent(5, firmware::LogLevel::Error);
    ASSERT_GE(errors.size(), 1u);
    EXPECT_NE(errors.back().find("error one"), std::string::npos);
    const auto all = recent(3, firmware::LogLevel::Debug);
    ASSERT_EQ(all.size(), 3u);
    EXPECT_NE(all[0].find("info 29"), std::string::npos);
    EXPECT_NE(all[2].find("debug three"), std::string::npos);
}

TEST(Log, OnTheJournalEachLineCarriesItsPriority)
{
    CapturedLog capture;
    struct stat st {};
    ASSERT_EQ(::fstat(capture.fds[1], &st), 0);
    const std::string stream = std::to_string(st.st_dev) + ":" +
                               std::to_string(static_cast<unsigned long long>(st.st_ino));
    ::setenv("JOURNAL_STREAM", stream.c_str(), 1);
    firmware::setLogFd(capture.fds[1]);  // systemd's stream: "<N>" prefixes
    EXPECT_TRUE(firmware::logsToJournal());
    MIRROR_LOG_ERROR("to the journal");
    MIRROR_LOG_WARN("to the journal");
    MIRROR_LOG_INFO("to the journal");
    MIRROR_LOG_DEBUG("to the journal");
    ::unsetenv("JOURNAL_STREAM");
    firmware::setLogFd(capture.fds[1]);  // not the journal: plain lines
    EXPECT_FALSE(firmware::logsToJournal());
    MIRROR_LOG_WARN("to a terminal");
    const std::string text = capture.text();
    for (const char* expected : {"<3>[", "<4>[", "<6>[", "<7>["})
        EXPECT_NE(text.find(expected), std::string::npos) << expected << " in " << text;
    EXPECT_NE(text.find("\n["), std::string::npos) << text;
    EXPECT_EQ(text.find("<4>[", text.find("to a terminal") - 20), std::string::npos) << text;
    // The ring (what `log` shows) never has the prefix.
    const auto lines = recent(2, firmware::LogLevel::Debug);
    EXPECT_EQ(lines[0].rfind("[", 0), 0u) << lines[0];
}

}  // namespace
