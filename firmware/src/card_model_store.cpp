#include "firmware/card_model_store.hpp"

#include "atomic_file.hpp"
#include "state_file.hpp"

#include <toml++/toml.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace firmware {

namespace {

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
    usable_ = createStateFolder(dir_, error_, sizeof error_);
}

std::optional<vision::CardColorModel> CardModelStore::load(std::string& warning) const
{
    const std::optional<toml::table> parsed = readStateToml(path_, warning);
    if (!parsed)
        return std::nullopt;
    const toml::table& table = *parsed;
    vision::CardColorModel model;
    // A sigma under 1 would make the colour test divide by (almost) zero; training floors it at
    // the tracker's minimum sigma (8 by default), so only an edited or foreign file has one.
    if (!readTriple(table, "mean", model.mean, 0.f, 255.f) ||
        !readTriple(table, "sigma", model.sigma, 1.f, 255.f)) {
        warning = path_ +
                  ": not a card model (needs mean, 3 numbers 0..255, and sigma, 3 numbers "
                  "1..255); ignored";
        return std::nullopt;
    }
    model.valid = true;
    return model;
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
    return writeFileAtomically(dir_.c_str(), path_.c_str(), tempPath_.c_str(), text,
                               static_cast<std::size_t>(n), error_, sizeof error_);
}

bool CardModelStore::remove() noexcept
{
    if (::unlink(path_.c_str()) == 0 || errno == ENOENT)
        return true;
    std::snprintf(error_, sizeof error_, "cannot remove %s: %s", path_.c_str(),
                  std::strerror(errno));
    return false;
}

}  // namespace firmware
