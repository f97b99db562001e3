#pragma once
// Display modes: parsing "WxH[@Hz]" and choosing one of the modes a connector offers. Pure
// functions over plain structs, so they are tested without a display.

#include <span>
#include <string>
#include <string_view>

namespace platform {

/// What the config asks for. width == 0: the connector's preferred mode.
struct DisplayModeRequest {
    int width = 0;
    int height = 0;
    double refreshHz = 0.0;  ///< 0: any (the preferred, else the fastest, of that size)
    bool preferred() const noexcept { return width == 0; }
};

/// Parses "", "preferred", "WxH" or "WxH@Hz" (e.g. "1280x720@60", "1920x1080@59.94"). False with
/// `error` set ("display mode ...: expected WxH or WxH@Hz") on anything else.
bool parseDisplayMode(std::string_view text, DisplayModeRequest& out, std::string& error);

/// One mode of a connector, as DRM lists it.
struct DisplayModeCandidate {
    int width = 0;
    int height = 0;
    double refreshHz = 0.0;
    bool preferred = false;   ///< DRM_MODE_TYPE_PREFERRED
    bool interlaced = false;  ///< never chosen
};

/// Index of the mode to set, or -1 when the connector has none matching. Preferred request: the
/// mode flagged preferred, else the first (drivers list the best first). WxH: the mode of that
/// size whose refresh is nearest `refreshHz` (within 1 Hz), or without a rate the preferred one of
/// that size, else the fastest. Interlaced modes are skipped.
int chooseDisplayMode(std::span<const DisplayModeCandidate> modes,
                      const DisplayModeRequest& request) noexcept;

/// E.g. "1024x768@60.00".
std::string displayModeName(const DisplayModeCandidate& mode);

}  // namespace platform
