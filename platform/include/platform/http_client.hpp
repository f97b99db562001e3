#pragma once
// HttpClient: one bounded HTTP(S) GET at a time through libcurl, for background threads only (a
// call blocks up to its timeout; the frame loop never makes one). Only http and https, also on
// redirects (at most 3); the answer is refused once it grows past its size limit, so a broken or
// hostile server costs a bounded time and memory. Errors are one line, never exceptions.

#include <chrono>
#include <cstddef>
#include <string>

namespace platform {

struct HttpResponse {
    bool ok = false;   ///< a 2xx answer arrived whole, within the time and size limits
    long status = 0;   ///< the HTTP status (0: no answer)
    std::string body;  ///< the answer (also of a non-2xx status, up to the limit)
    /// Why not ok, one line: "HTTP 500", "timed out after 10 s", "connection refused (...)",
    /// "the answer is over 1048576 bytes", "URL must start with http:// or https://".
    std::string problem;
};

class HttpClient {
public:
    /// Throws std::runtime_error (one line) when libcurl cannot be set up.
    explicit HttpClient(std::string userAgent = "mirror");
    ~HttpClient();
    HttpClient(const HttpClient&) = delete;
    HttpClient& operator=(const HttpClient&) = delete;

    HttpResponse get(const std::string& url, std::chrono::milliseconds timeout,
                     std::size_t maxBytes);

private:
    void* curl_ = nullptr;  // CURL*, kept for its connection cache
    std::string userAgent_;
};

}  // namespace platform
