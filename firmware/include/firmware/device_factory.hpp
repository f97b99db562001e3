#pragma once
// Builds the frame source and the display named by the config's specs ("auto", "demo",
// "synthetic", "file:PATH", "headless:DIR", ...). One implementation per device, chosen here only.

#include "firmware/config.hpp"
#include "firmware/device_wait.hpp"
#include "platform/button_input.hpp"
#include "platform/display.hpp"
#include "platform/frame_source.hpp"

#include <memory>

namespace firmware {

/// Debian's opencv-doc sample video, the real scene of the demo (a face; 720x528).
inline constexpr const char* kDemoVideoPath =
    "/usr/share/doc/opencv-doc/examples/data/Megamind.avi";

/// Opens the source. Throws StartupError(kExitSource) with one line on failure.
std::unique_ptr<platform::FrameSource> makeSource(const SourceConfig& config);
/// Opens the display. Throws StartupError(kExitDisplay) with one line on failure. A DRM panel
/// without [display] snapshot_dir keeps its snapshots in `stateDir`/snapshots (none when empty).
std::unique_ptr<platform::Display> makeDisplay(const DisplayConfig& config,
                                               const std::string& stateDir = {});
/// What an appliance whose `auto` source or display found nothing waits for (DeviceWait on udev's
/// events and the factory's own device checks); null when it waits for nothing. `source` and
/// `display` are what makeSource and makeDisplay made from `config`.
std::unique_ptr<DeviceWait> makeDeviceWait(const Config& config,
                                           const platform::FrameSource& source,
                                           const platform::Display& display);
/// Opens the GPIO buttons, or returns null: when disabled, and when the chip is missing or busy
/// (logged as one warning: the mirror runs on with its other inputs).
std::unique_ptr<platform::ButtonInput> makeButtons(const ButtonsConfig& config);

}  // namespace firmware
