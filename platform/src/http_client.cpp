#include "platform/http_client.hpp"

#include <curl/curl.h>

#include <mutex>
#include <stdexcept>

namespace platform {

namespace {

// curl_global_init is not thread-safe and must run once before any handle.
void initialiseCurlOnce()
{
    static std::once_flag once;
    static CURLcode result = CURLE_OK;
    std::call_once(once, [] { result = curl_global_init(CURL_GLOBAL_DEFAULT); });
    if (result != CURLE_OK)
        throw std::runtime_error(std::string("libcurl: ") + curl_easy_strerror(result));
}

struct Sink {
    std::string* body;
    std::size_t maxBytes;
    bool overflow = false;
};

std::size_t append(char* data, std::size_t size, std::size_t count, void* user)
{
    Sink& sink = *static_cast<Sink*>(user);
    const std::size_t n = size * count;
    if (sink.body->size() + n > sink.maxBytes) {
        sink.overflow = true;
        return 0;  // libcurl stops with CURLE_WRITE_ERROR
    }
    sink.body->append(data, n);
    return n;
}

}  // namespace

HttpClient::HttpClient(std::string userAgent) : userAgent_(std::move(userAgent))
{
    initialiseCurlOnce();
    curl_ = curl_easy_init();
    if (curl_ == nullptr)
        throw std::runtime_error("libcurl: cannot create a handle");
}

HttpClient::~HttpClient()
{
    curl_easy_cleanup(static_cast<CURL*>(curl_));
}

HttpResponse HttpClient::get(const std::string& url, std::chrono::milliseconds timeout,
                             std::size_t maxBytes)
{
    HttpResponse r;
    if (url.rfind("http://", 0) != 0 && url.rfind("https://", 0) != 0) {
        r.problem = "URL must start with http:// or https://";
        return r;
    }
    CURL* c = static_cast<CURL*>(curl_);
    curl_easy_reset(c);
    char error[CURL_ERROR_SIZE] = "";
    Sink sink{&r.body, maxBytes};
    curl_easy_setopt(c, CURLOPT_URL, url.c_str());
    curl_easy_setopt(c, CURLOPT_PROTOCOLS_STR, "http,https");
    curl_easy_setopt(c, CURLOPT_REDIR_PROTOCOLS_STR, "http,https");
    curl_easy_setopt(c, CURLOPT_FOLLOWLOCATION, 1L);
    curl_easy_setopt(c, CURLOPT_MAXREDIRS, 3L);
    curl_easy_setopt(c, CURLOPT_NOSIGNAL, 1L);  // other threads: no SIGALRM for DNS timeouts
    curl_easy_setopt(c, CURLOPT_TIMEOUT_MS, static_cast<long>(timeout.count()));
    curl_easy_setopt(c, CURLOPT_CONNECTTIMEOUT_MS, static_cast<long>(timeout.count()));
    curl_easy_setopt(c, CURLOPT_USERAGENT, userAgent_.c_str());
    curl_easy_setopt(c, CURLOPT_ACCEPT_ENCODING, "");  // whatever libcurl can decode
    curl_easy_setopt(c, CURLOPT_WRITEFUNCTION, append);
    curl_easy_setopt(c, CURLOPT_WRITEDATA, &sink);
    curl_easy_setopt(c, CURLOPT_ERRORBUFFER, error);
    const CURLcode result = curl_easy_perform(c);
    curl_easy_getinfo(c, CURLINFO_RESPONSE_CODE, &r.status);
    if (sink.overflow) {
        r.problem = "the answer is over " + std::to_string(maxBytes) + " bytes";
    } else if (result == CURLE_OPERATION_TIMEDOUT) {
        r.problem = "timed out after " + (timeout.count() % 1000 == 0
                                              ? std::to_string(timeout.count() / 1000) + " s"
                                              : std::to_string(timeout.count()) + " ms");
    } else if (result != CURLE_OK) {
        r.problem = error[0] != '\0' ? error : curl_easy_strerror(result);
    } else if (r.status < 200 || r.status > 299) {
        r.problem = "HTTP " + std::to_string(r.status);
    } else {
        r.ok = true;
    }
    for (char& ch : r.problem)
        if (ch == '\n' || ch == '\r')
            ch = ' ';
    return r;
}

}  // namespace platform
