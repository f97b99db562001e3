// The weather forecast: Open-Meteo's answers parsed, and the background service against a local
// HTTP server on 127.0.0.1 that answers well, slowly, with garbage or with 500, or is not there;
// the cache in the state folder keeping the last forecast when the source is down.
#include "firmware/weather_service.hpp"

#include "firmware/log.hpp"
#include "firmware/weather_forecast.hpp"
#include "test_paths.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>

namespace {

using namespace std::chrono_literals;
using firmware::WeatherService;
using firmware::WeatherServiceOptions;

// A one-connection-at-a-time HTTP/1.1 server on an ephemeral port of 127.0.0.1.
class LocalHttpServer {
public:
    enum class Mode { Good, Slow, Garbage, Error500 };

    LocalHttpServer()
    {
        fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t len = sizeof a;
        if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
            ::listen(fd_, 8) != 0 || ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0)
            throw std::runtime_error("local HTTP server: cannot listen");
        port_ = ntohs(a.sin_port);
        thread_ = std::thread([this] { serve(); });
    }
    ~LocalHttpServer()
    {
        stop_ = true;
        thread_.join();
        ::close(fd_);
    }

    std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1/forecast"; }
    void answer(Mode mode, std::string body = "")
    {
        mode_ = mode;
        const std::lock_guard<std::mutex> lock(mutex_);
        body_ = std::move(body);
    }
    int requests() const { return requests_; }

private:
    void serve()
    {
        while (!stop_) {
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, 20) <= 0)
                continue;
            const int c = ::accept(fd_, nullptr, nullptr);
            if (c < 0)
                continue;
            std::string request;
            char buffer[1024];
            while (request.find("\r\n\r\n") == std::string::npos) {
                const ssize_t n = ::read(c, buffer, sizeof buffer);
                if (n <= 0)
                    break;
                request.append(buffer, static_cast<std::size_t>(n));
            }
            ++requests_;
            std::string body;
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                body = body_;
            }
            std::string reply;
            switch (mode_.load()) {
                case Mode::Slow:
                    for (int i = 0; i < 100 && !stop_; ++i)  // 2 s, longer than the tests' timeout
                        std::this_thread::sleep_for(20ms);
                    [[fallthrough]];
                case Mode::Good:
                    reply =
                        "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: " +
                        std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body;
                    break;
                case Mode::Garbage:
                    reply =
                        "HTTP/1.1 200 OK\r\nContent-Length: 19\r\nConnection: close\r\n\r\n"
                        "<html>oops</html>\r\n";
                    break;
                case Mode::Error500:
                    reply =
                        "HTTP/1.1 500 Internal Server Error\r\nContent-Length: 0\r\n"
                        "Connection: close\r\n\r\n";
                    break;
            }
            [[maybe_unused]] const ssize_t written = ::write(c, reply.data(), reply.size());
            ::close(c);
        }
    }

    int fd_ = -1;
    int port_ = 0;
    std::atomic<bool> stop_{false};
    std::atomic<Mode> mode_{Mode::Good};
    std::atomic<int> requests_{0};
    std::mutex mutex_;
    std::string body_;
    std::thread thread_;
};

// A port nothing listens on (bound, then closed).
int refusedPort()
{
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    ::close(fd);
    return ntohs(a.sin_port);
}

std::string openMeteo(int code)
{
    return R"({"latitude":52.52,"longitude":13.42,"current_units":{"weather_code":"wmo code"},)"
           R"("current":{"time":"2026-12-03T10:00","interval":900,"weather_code":)" +
           std::to_string(code) + "}}";
}

// Waits (up to 10 s: the machine may be loaded) until `done` holds.
template <typename F>
bool eventually(F done)
{
    for (int i = 0; i < 1000 && !done(); ++i)
        std::this_thread::sleep_for(10ms);
    return done();
}

WeatherServiceOptions fast(const std::string& source, const std::string& dir)
{
    WeatherServiceOptions o;
    o.source = source;
    o.interval = 60s;
    o.timeout = 300ms;
    o.firstRetry = 50ms;
    o.cacheDir = dir;
    return o;
}

std::string describe(const WeatherService& s)
{
    char line[512];
    s.describe(line, sizeof line, static_cast<std::int64_t>(std::time(nullptr)));
    return line;
}

std::string readAll(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(WeatherForecast, ReadsOpenMeteosCodesAndRefusesAnythingElse)
{
    int code = -1;
    std::string problem;
    EXPECT_TRUE(firmware::parseForecast(openMeteo(61), code, problem)) << problem;
    EXPECT_EQ(code, 61);
    EXPECT_TRUE(firmware::parseForecast(R"({"current_weather":{"weathercode":3}})", code, problem));
    EXPECT_EQ(code, 3);
    EXPECT_TRUE(firmware::parseForecast(R"({"daily":{"weather_code":[71,0,0]}})", code, problem));
    EXPECT_EQ(code, 71);
    EXPECT_TRUE(
        firmware::parseForecast(firmware::forecastCacheText(95, 1700000000), code, problem));
    EXPECT_EQ(code, 95);
    EXPECT_EQ(firmware::fetchedUnixOf(firmware::forecastCacheText(95, 1700000000)), 1700000000);

    const std::pair<const char*, const char*> bad[] = {
        {"<html>", "not JSON"},
        {R"({"current":{"temperature":3}})", "no weather code"},
        {R"({"current":{"weather_code":"61"}})", "no weather code"},
        {R"({"current":{"weather_code":61.5}})", "no weather code"},
        {R"({"current":{"weather_code":150}})", "not a WMO code"},
        {R"({"daily":{"weather_code":[]}})", "no weather code"},
        {"[1,2]", "no weather code"},
    };
    for (const auto& [text, why] : bad) {
        problem.clear();
        EXPECT_FALSE(firmware::parseForecast(text, code, problem)) << text;
        EXPECT_NE(problem.find(why), std::string::npos) << text << ": " << problem;
    }
    // A hostile answer nested a million deep is refused before the parser recurses into it.
    EXPECT_FALSE(firmware::parseForecast(std::string(1'000'000, '['), code, problem));
    EXPECT_NE(problem.find("nested deeper than 64"), std::string::npos) << problem;
}

TEST(WeatherForecast, TheConfigMapsCodesToOverlays)
{
    const std::vector<firmware::WeatherOverlay> kinds = {
        {"sun", "sun_hat", {0, 1}}, {"rain", "rain_hat", {61, 63}}, {"snow", "", {71}}};
    EXPECT_EQ(firmware::overlayForWeather(kinds, 1), "sun_hat");
    EXPECT_EQ(firmware::overlayForWeather(kinds, 63), "rain_hat");
    EXPECT_EQ(firmware::overlayForWeather(kinds, 71), "");
    EXPECT_EQ(firmware::overlayForWeather(kinds, 45), "");
    EXPECT_EQ(firmware::overlayForWeather(kinds, -1), "");
    EXPECT_STREQ(firmware::weatherCodeText(63), "rain");
    EXPECT_STREQ(firmware::weatherCodeText(-1), "no forecast");
}

TEST(WeatherService, AGoodAnswerIsUsedAndCachedAtomically)
{
    LocalHttpServer server;
    server.answer(LocalHttpServer::Mode::Good, openMeteo(61));
    const std::string dir = testing_support::freshOutputDir("weather_good");
    {
        WeatherService weather(fast(server.url(), dir));
        ASSERT_TRUE(eventually([&] { return weather.goodFetches() >= 1; })) << describe(weather);
        EXPECT_EQ(weather.code(), 61);
        EXPECT_GT(weather.fetchedUnix(), 1'700'000'000);
        EXPECT_NE(describe(weather).find("rain (code 61) fetched 0 min ago from http://127.0.0.1"),
                  std::string::npos)
            << describe(weather);
    }
    EXPECT_NE(readAll(dir + "/weather.json").find("\"weather_code\":61"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir + "/weather.json.tmp"));
}

TEST(WeatherService, WhenTheSourceFailsTheLastForecastStaysWithOneWarningPerOutage)
{
    struct Case {
        LocalHttpServer::Mode mode;
        const char* problem;
    };
    for (const Case c : {Case{LocalHttpServer::Mode::Slow, "timed out after 300 ms"},
                         Case{LocalHttpServer::Mode::Garbage, "not JSON"},
                         Case{LocalHttpServer::Mode::Error500, "HTTP 500"}}) {
        LocalHttpServer server;
        server.answer(c.mode, openMeteo(61));
        const std::string dir = testing_support::freshOutputDir("weather_failing");
        std::ofstream(dir + "/weather.json") << firmware::forecastCacheText(3, 1'700'000'000);
        const std::string log = dir + "/log.txt";
        const int logFd = ::open(log.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0600);
        firmware::setLogFd(logFd);
        {
            WeatherService weather(fast(server.url(), dir));
            EXPECT_EQ(weather.code(), 3) << "the cached forecast, before any fetch";
            EXPECT_EQ(weather.fetchedUnix(), 1'700'000'000);
            ASSERT_TRUE(eventually([&] { return weather.failedFetches() >= 2; }))
                << describe(weather);
            EXPECT_EQ(weather.code(), 3) << c.problem;
            EXPECT_EQ(weather.goodFetches(), 0);
            EXPECT_NE(describe(weather).find(std::string("the last try failed: ") + c.problem),
                      std::string::npos)
                << describe(weather);
        }
        firmware::setLogFd(2);
        ::close(logFd);
        const std::string text = readAll(log);
        std::size_t warnings = 0;
        for (std::size_t at = text.find("W weather:"); at != std::string::npos;
             at = text.find("W weather:", at + 1))
            ++warnings;
        EXPECT_EQ(warnings, 1u) << text;
        EXPECT_NE(text.find("keeping the last forecast"), std::string::npos) << text;
        EXPECT_NE(readAll(dir + "/weather.json").find("\"weather_code\":3"), std::string::npos)
            << "a failed fetch leaves the cache alone";
    }
}

TEST(WeatherService, ARefusedConnectionBacksOffAndTheCacheIsUsed)
{
    const std::string dir = testing_support::freshOutputDir("weather_refused");
    std::ofstream(dir + "/weather.json") << firmware::forecastCacheText(71, 1'700'000'000);
    WeatherService weather(
        fast("http://127.0.0.1:" + std::to_string(refusedPort()) + "/forecast", dir));
    EXPECT_EQ(weather.code(), 71);
    ASSERT_TRUE(eventually([&] { return weather.failedFetches() >= 2; })) << describe(weather);
    EXPECT_NE(describe(weather).find("Couldn't connect"), std::string::npos) << describe(weather);
    // Retries after 50, 100, 200, 400 ms ...: a few in a second, not one every 50 ms.
    std::this_thread::sleep_for(1s);
    EXPECT_LE(weather.failedFetches(), 7);
    EXPECT_EQ(weather.code(), 71);
}

TEST(WeatherService, AFileWrittenByAnotherServiceIsASourceAndACorruptCacheIsIgnored)
{
    const std::string dir = testing_support::freshOutputDir("weather_file");
    std::ofstream(dir + "/weather.json") << "{\"current\":{\"weather_";  // cut short by a power cut
    std::ofstream(dir + "/forecast.json") << openMeteo(0);
    WeatherService weather(fast("file:" + dir + "/forecast.json", dir));
    ASSERT_TRUE(eventually([&] { return weather.goodFetches() >= 1; })) << describe(weather);
    EXPECT_EQ(weather.code(), 0);

    WeatherService missing(fast("file:" + dir + "/none.json", ""));
    ASSERT_TRUE(eventually([&] { return missing.failedFetches() >= 1; }));
    EXPECT_EQ(missing.code(), -1);
    EXPECT_NE(describe(missing).find("no forecast"), std::string::npos) << describe(missing);

    EXPECT_THROW(WeatherService(fast("ftp://example.org/x", "")), std::invalid_argument);
    WeatherService off(fast("", dir));
    EXPECT_EQ(off.failedFetches() + off.goodFetches(), 0);
}

}  // namespace
