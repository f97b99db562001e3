#pragma once
// What DrmDisplay drives, chosen at start-up: the card with a connected connector, the connector's
// mode the config asks for, and a CRTC that can drive it. Private to platform/src.

#include "platform/display_mode.hpp"

#include <xf86drmMode.h>

#include <cstdint>
#include <string>

namespace platform {

/// An open card, its connected connector, the mode chosen on it and a CRTC for it.
struct DrmOutput {
    std::string cardPath;  ///< e.g. "/dev/dri/card0"
    int fd = -1;           ///< the open card; the caller closes it
    std::uint32_t connectorId = 0;
    std::string connectorName;  ///< e.g. "Virtual-1"
    drmModeModeInfo mode{};
    std::uint32_t crtcId = 0;
};

/// Opens `card` ("" = the first /dev/dri/cardN with a connected connector), chooses the mode that
/// `mode` names (parseDisplayMode) and a CRTC. Throws std::runtime_error ("drm: ...") naming the
/// card and the reason: bad mode text, no card, no connected connector, no such mode, no CRTC; the
/// card is closed again then.
DrmOutput chooseDrmOutput(const std::string& card, const std::string& mode);

/// The mode as display_mode.hpp sees it, its refresh rate from the timings.
DisplayModeCandidate displayModeCandidateOf(const drmModeModeInfo& mode) noexcept;

/// Throws std::runtime_error("drm: CARD: what"), or "drm: what" when `cardPath` is empty.
[[noreturn]] void throwDrmError(const std::string& cardPath, const std::string& what);

}  // namespace platform
