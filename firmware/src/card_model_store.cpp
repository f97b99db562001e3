#include "firmware/card_model_store.hpp"

#include <fcntl.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace firmware {

namespace {

bool writeAll(int fd, const char* data, std::size_t size) noexcept
{
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

/// Three finite numbers in a sane chromaticity range, or nothing.
bool readTriple(const toml::table& table, const char* key, float out[3], float lo, float hi)
{
    const toml::array* a = table[key].as_array();
    if (!a || a->size() != 3)
        return false;
    for (std::size_t i = 0; i < 3; ++i) {
        const std::optional<double> v = (*a)[i].value<double>();
        if (!v || !std::isfinite(*v) || *v < lo || *v > hi)
            return false;
        out[i] = static_cast<float>(*v);
    }
    return true;
}

}  // namespace

CardModelStore::CardModelStore(const std::string& stateDir)
    : dir_(stateDir), path_(stateDir + "/card-model.toml"), tempPath_(path_ + ".tmp")
{
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    if (ec) {
        std::snprintf(error_, sizeof error_, "state folder %s: %s", dir_.c_str(),
                      ec.message().c_str());
        return;
    }
    usable_ = true;
}

std::optional<vision::CardColorModel> CardModelStore::load(std::string& warning) const
{
    warning.clear();
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec))
        return std::nullopt;
    try {
        const toml::table table = toml::parse_file(path_);
        vision::CardColorModel model;
        if (!readTriple(table, "mean", model.mean, 0.f, 255.f) ||
            !readTriple(table, "sigma", model.sigma, 0.f, 255.f)) {
            warning =
                path_ + ": not a card model (needs mean and sigma, 3 numbers 0..255 each); ignored";
            return std::nullopt;
        }
        model.valid = true;
        return model;
    } catch (const toml::parse_error& e) {
        warning = path_ + ":" + std::to_string(e.source().begin.line) + ":" +
                  std::to_string(e.source().begin.column) + ": " + std::string(e.description()) +
                  "; ignored";
        return std::nullopt;
    }
}

bool CardModelStore::save(const vision::CardColorModel& model) noexcept
{
    if (!usable_)
        return false;
    char text[256];
    const int n =
        std::snprintf(text, sizeof text,
                      "# trained card colour (chromaticity, 0..255), written by `card train`\n"
                      "mean = [%.3f, %.3f, %.3f]\nsigma = [%.3f, %.3f, %.3f]\n",
                      static_cast<double>(model.mean[0]), static_cast<double>(model.mean[1]),
                      static_cast<double>(model.mean[2]), static_cast<double>(model.sigma[0]),
                      static_cast<double>(model.sigma[1]), static_cast<double>(model.sigma[2]));
    const int fd = ::open(tempPath_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        std::snprintf(error_, sizeof error_, "%s: %s", tempPath_.c_str(), std::strerror(errno));
        return false;
    }
    const bool written = writeAll(fd, text, static_cast<std::size_t>(n)) && ::fsync(fd) == 0;
    const int writeErrno = errno;
    ::close(fd);
    if (!written || ::rename(tempPath_.c_str(), path_.c_str()) != 0) {
        std::snprintf(error_, sizeof error_, "%s: %s", path_.c_str(),
                      std::strerror(written ? errno : writeErrno));
        ::unlink(tempPath_.c_str());
        return false;
    }
    // The rename is durable only once the folder's entry is on disk too.
    const int dirFd = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd >= 0) {
        ::fsync(dirFd);
        ::close(dirFd);
    }
    error_[0] = '\0';
    return true;
}

}  // namespace firmware
