#include "firmware/weather_service.hpp"

#include "atomic_file.hpp"
#include "firmware/log.hpp"
#include "firmware/weather_forecast.hpp"
#include "platform/http_client.hpp"
#include "vision/bounded_file.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <memory>
#include <stdexcept>

namespace firmware {

namespace {

// A forecast is a few kilobytes; anything much larger is not one.
constexpr std::size_t kMaxAnswerBytes = 256 * 1024;
constexpr const char* kCacheName = "weather.json";

bool isUrl(const std::string& s)
{
    return s.rfind("http://", 0) == 0 || s.rfind("https://", 0) == 0;
}

std::int64_t nowUnix()
{
    return static_cast<std::int64_t>(std::time(nullptr));
}

}  // namespace

WeatherService::WeatherService(WeatherServiceOptions options) : options_(std::move(options))
{
    if (!options_.source.empty() && !isUrl(options_.source) &&
        options_.source.rfind("file:", 0) != 0)
        throw std::invalid_argument("weather source '" + options_.source +
                                    "' is neither an http(s):// URL nor file:PATH");
    loadCache();
    if (!options_.source.empty())
        thread_ = std::thread([this] { run(); });
}

WeatherService::~WeatherService()
{
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable())
        thread_.join();
}

void WeatherService::loadCache()
{
    if (options_.cacheDir.empty())
        return;
    const std::string path = options_.cacheDir + "/" + kCacheName;
    const vision::BoundedFile f = vision::readBoundedFile(path, kMaxAnswerBytes);
    if (f.status == vision::BoundedFile::Status::Missing)
        return;
    int code = -1;
    std::string problem = f.problem;
    if (f.status == vision::BoundedFile::Status::Ok && parseForecast(f.text, code, problem)) {
        store(code, fetchedUnixOf(f.text));
        MIRROR_LOG_INFO("weather: the last forecast from %s: %s (code %d)", path.c_str(),
                        weatherCodeText(code), code);
        return;
    }
    MIRROR_LOG_WARN("weather: ignoring the cached forecast %s: %s", path.c_str(), problem.c_str());
}

void WeatherService::store(int code, std::int64_t fetchedUnix)
{
    fetchedUnix_.store(fetchedUnix);
    code_.store(code, std::memory_order_release);
}

bool WeatherService::fetchOnce(platform::HttpClient* http, std::string& problem)
{
    std::string body;
    if (http != nullptr) {
        platform::HttpResponse r = http->get(options_.source, options_.timeout, kMaxAnswerBytes);
        if (!r.ok) {
            problem = r.problem;
            return false;
        }
        body = std::move(r.body);
    } else {
        const vision::BoundedFile f =
            vision::readBoundedFile(options_.source.substr(5), kMaxAnswerBytes);
        if (f.status != vision::BoundedFile::Status::Ok) {
            problem = f.problem;
            return false;
        }
        body = f.text;
    }
    int code = -1;
    if (!parseForecast(body, code, problem))
        return false;
    const std::int64_t when = nowUnix();
    store(code, when);
    if (!options_.cacheDir.empty()) {
        const std::string text = forecastCacheText(code, when);
        const std::string path = options_.cacheDir + "/" + kCacheName;
        const std::string temp = path + ".tmp";
        char error[256] = "";
        if (!writeFileAtomically(options_.cacheDir.c_str(), path.c_str(), temp.c_str(), text.data(),
                                 text.size(), error, sizeof error))
            MIRROR_LOG_WARN("weather: forecast not cached: %s", error);
    }
    return true;
}

void WeatherService::run()
{
    // One client for the thread's life: it keeps the connection (and TLS session) between fetches.
    std::unique_ptr<platform::HttpClient> http;
    if (isUrl(options_.source)) {
        try {
            http = std::make_unique<platform::HttpClient>("mirror/" MIRROR_VERSION);
        } catch (const std::exception& e) {
            MIRROR_LOG_ERROR("weather: no forecast: %s", e.what());
            return;
        }
    }
    int streak = 0;  // failures in a row
    for (;;) {
        std::string problem;
        const bool ok = fetchOnce(http.get(), problem);
        std::chrono::milliseconds wait = options_.interval;
        if (ok) {
            ++good_;
            if (streak > 0)
                MIRROR_LOG_INFO("weather: %s answers again: %s (code %d)", options_.source.c_str(),
                                weatherCodeText(code()), code());
            streak = 0;
            const std::lock_guard<std::mutex> lock(mutex_);
            problem_[0] = '\0';
        } else {
            ++failed_;
            // One warning per outage, not one per try.
            if (streak == 0)
                MIRROR_LOG_WARN("weather: %s: %s; %s", options_.source.c_str(), problem.c_str(),
                                code() >= 0 ? "keeping the last forecast" : "no forecast yet");
            const int doublings = std::min(streak, 16);
            wait = std::min(options_.interval,
                            std::chrono::milliseconds(options_.firstRetry.count() << doublings));
            ++streak;
            const std::lock_guard<std::mutex> lock(mutex_);
            std::snprintf(problem_, sizeof problem_, "%s", problem.c_str());
        }
        std::unique_lock<std::mutex> lock(mutex_);
        if (wake_.wait_for(lock, wait, [this] { return stop_; }))
            return;
    }
}

void WeatherService::describe(char* out, std::size_t capacity, std::int64_t now) const noexcept
{
    if (capacity == 0)
        return;
    const int c = code();
    const std::int64_t when = fetchedUnix();
    const char* source = options_.source.empty() ? "no source configured" : options_.source.c_str();
    int n = 0;
    if (c < 0)
        n = std::snprintf(out, capacity, "no forecast (%s)", source);
    else if (when > 0) {
        const long long minutes = std::max<long long>(0, (now - when) / 60);
        const long long amount = minutes < 120    ? minutes
                                 : minutes < 2880 ? minutes / 60
                                                  : minutes / 1440;
        const char* unit = minutes < 120 ? "min" : minutes < 2880 ? "h" : "days";
        n = std::snprintf(out, capacity, "%s (code %d) fetched %lld %s ago from %s",
                          weatherCodeText(c), c, amount, unit, source);
    } else
        n = std::snprintf(out, capacity, "%s (code %d) from %s", weatherCodeText(c), c, source);
    const std::lock_guard<std::mutex> lock(mutex_);
    if (problem_[0] != '\0' && n >= 0 && static_cast<std::size_t>(n) < capacity)
        std::snprintf(out + n, capacity - static_cast<std::size_t>(n), "; the last try failed: %s",
                      problem_);
}

}  // namespace firmware
