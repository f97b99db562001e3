#pragma once
// WeatherService: keeps the current weather code from a forecast source, fetched in the
// background (never in the frame loop) at an interval, with back-off after failures, and cached
// atomically in the state folder so a mirror without network keeps its last forecast across
// restarts. A source that is down, slow or answers garbage costs one warning per outage; the last
// good forecast stays.
//
// Sources (`[weather] source`): an http:// or https:// URL answering Open-Meteo's JSON (e.g.
// https://api.open-meteo.com/v1/forecast?latitude=52.52&longitude=13.41&current=weather_code), or
// file:/path/to/forecast.json that another service writes in the same format.
//
// Threads: the fetching thread writes; the frame loop and the console read code() and
// fetchedUnix() (atomics) and describe() (a short lock, no allocation).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace platform {
class HttpClient;
}

namespace firmware {

struct WeatherServiceOptions {
    std::string source;                             ///< URL or file:PATH; "" = no forecast
    std::chrono::milliseconds interval{1'800'000};  ///< between good fetches
    std::chrono::milliseconds timeout{10'000};      ///< one fetch at most
    std::chrono::milliseconds firstRetry{30'000};   ///< after a failure; doubles up to interval
    std::string cacheDir;                           ///< the state folder (weather.json); "" = none
};

class WeatherService {
public:
    /// Reads the cache (a corrupt one is a warning and ignored) and starts fetching when there is
    /// a source. Throws std::invalid_argument (one line) for a source of an unknown kind.
    explicit WeatherService(WeatherServiceOptions options);
    /// Stops the thread; a fetch under way ends within its timeout.
    ~WeatherService();
    WeatherService(const WeatherService&) = delete;
    WeatherService& operator=(const WeatherService&) = delete;

    /// The last good WMO weather code, -1 while there is none.
    int code() const noexcept { return code_.load(std::memory_order_acquire); }
    /// When it was fetched (Unix seconds), 0 while there is none.
    std::int64_t fetchedUnix() const noexcept { return fetchedUnix_.load(); }
    /// Fetches that succeeded and failed since start (tests, status).
    int goodFetches() const noexcept { return good_.load(); }
    int failedFetches() const noexcept { return failed_.load(); }
    /// One line for `status`, e.g. "rain (code 61) fetched 12 min ago from https://...; the
    /// last try failed: timed out after 10 s". No allocation.
    void describe(char* out, std::size_t capacity, std::int64_t nowUnix) const noexcept;

private:
    void run();
    bool fetchOnce(platform::HttpClient* http, std::string& problem);
    void store(int code, std::int64_t fetchedUnix);
    void loadCache();

    WeatherServiceOptions options_;
    std::atomic<int> code_{-1};
    std::atomic<std::int64_t> fetchedUnix_{0};
    std::atomic<int> good_{0}, failed_{0};
    mutable std::mutex mutex_;  // problem_, stop_
    char problem_[160] = "";
    bool stop_ = false;
    std::condition_variable wake_;
    std::thread thread_;
};

}  // namespace firmware
