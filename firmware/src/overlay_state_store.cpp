#include "firmware/overlay_state_store.hpp"

#include "atomic_file.hpp"
#include "state_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cstdio>

namespace firmware {

namespace {

bool isControl(char c)
{
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 || u == 0x7F;
}

}  // namespace

OverlayStateStore::OverlayStateStore(const std::string& stateDir)
    : dir_(stateDir), path_(stateDir + "/overlay.toml"), tempPath_(path_ + ".tmp")
{
    usable_ = createStateFolder(dir_, error_, sizeof error_);
}

std::optional<OverlayState> OverlayStateStore::load(std::string& warning) const
{
    const std::optional<toml::table> parsed = readStateToml(path_, warning);
    if (!parsed)
        return std::nullopt;
    const toml::table& table = *parsed;
    const std::optional<std::string> overlay = table["overlay"].value<std::string>();
    const std::optional<std::string> modeText = table["mode"].value<std::string>();
    OverlayState state;
    const bool nameOk = overlay && !overlay->empty() && overlay->size() <= kMaxNameLength &&
                        std::none_of(overlay->begin(), overlay->end(), isControl);
    if (!nameOk || !modeText || !parseOverlayMode(*modeText, state.mode)) {
        warning = path_ +
                  ": not an overlay state (needs overlay = \"NAME\" and mode = \"global\" or "
                  "\"per_face\"); ignored";
        return std::nullopt;
    }
    state.overlay = *overlay;
    return state;
}

bool OverlayStateStore::save(std::string_view overlay, OverlayMode mode) noexcept
{
    if (!usable_)
        return false;
    if (overlay.empty() || overlay.size() > kMaxNameLength) {
        std::snprintf(error_, sizeof error_, "%s: overlay name of %zu bytes not saved",
                      path_.c_str(), overlay.size());
        return false;
    }
    // A TOML basic string: quote and backslash escaped; control characters are refused.
    char name[2 * kMaxNameLength + 1];
    std::size_t n = 0;
    for (char c : overlay) {
        if (isControl(c)) {
            std::snprintf(error_, sizeof error_, "%s: control character in overlay name",
                          path_.c_str());
            return false;
        }
        if (c == '"' || c == '\\')
            name[n++] = '\\';
        name[n++] = c;
    }
    name[n] = '\0';
    char text[2 * kMaxNameLength + 160];
    const int length = std::snprintf(
        text, sizeof text,
        "# overlay selection, written when a button or the `overlay` command changes it\n"
        "overlay = \"%s\"\nmode = \"%s\"\n",
        name, toString(mode));
    return writeFileAtomically(dir_.c_str(), path_.c_str(), tempPath_.c_str(), text,
                               static_cast<std::size_t>(length), error_, sizeof error_);
}

bool OverlayStateStore::save(const OverlaySelection& selection) noexcept
{
    return save(selection.name(selection.selected()), selection.mode());
}

}  // namespace firmware
