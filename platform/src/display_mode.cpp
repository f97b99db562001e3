#include "platform/display_mode.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace platform {

namespace {

bool parseInt(std::string_view text, int& out)
{
    if (text.empty() || text.size() > 5)
        return false;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size() && out > 0;
}

bool parseHz(std::string_view text, double& out)
{
    // from_chars for double is in GCC 12's libstdc++; keep to a plain decimal.
    if (text.empty() || text.size() > 10)
        return false;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size() && std::isfinite(out) &&
           out > 0.0 && out < 1000.0;
}

}  // namespace

bool parseDisplayMode(std::string_view text, DisplayModeRequest& out, std::string& error)
{
    out = {};
    if (text.empty() || text == "preferred")
        return true;
    const std::string_view whole = text;
    std::string_view hz;
    if (const std::size_t at = text.find('@'); at != std::string_view::npos) {
        hz = text.substr(at + 1);
        text = text.substr(0, at);
        if (!parseHz(hz, out.refreshHz)) {
            error = "display mode " + std::string(whole) +
                    ": refresh rate must be a number of Hz (expected WxH or WxH@Hz)";
            return false;
        }
    }
    const std::size_t x = text.find('x');
    if (x == std::string_view::npos || !parseInt(text.substr(0, x), out.width) ||
        !parseInt(text.substr(x + 1), out.height)) {
        out = {};
        error = "display mode " + std::string(whole) +
                ": expected preferred, WxH or WxH@Hz (e.g. 1280x720@60)";
        return false;
    }
    return true;
}

int chooseDisplayMode(std::span<const DisplayModeCandidate> modes,
                      const DisplayModeRequest& request) noexcept
{
    int best = -1;
    for (std::size_t i = 0; i < modes.size(); ++i) {
        const DisplayModeCandidate& m = modes[i];
        if (m.interlaced)
            continue;
        const int index = static_cast<int>(i);
        if (request.preferred()) {
            if (m.preferred)
                return index;
            if (best < 0)
                best = index;
            continue;
        }
        if (m.width != request.width || m.height != request.height)
            continue;
        if (request.refreshHz > 0.0) {
            const double error = std::fabs(m.refreshHz - request.refreshHz);
            if (error < 1.0 &&
                (best < 0 || error < std::fabs(modes[best].refreshHz - request.refreshHz)))
                best = index;
        } else if (m.preferred) {
            return index;
        } else if (best < 0 || m.refreshHz > modes[best].refreshHz) {
            best = index;
        }
    }
    return best;
}

std::string displayModeName(const DisplayModeCandidate& mode)
{
    char text[48];
    std::snprintf(text, sizeof text, "%dx%d@%.2f", mode.width, mode.height, mode.refreshHz);
    return text;
}

}  // namespace platform
