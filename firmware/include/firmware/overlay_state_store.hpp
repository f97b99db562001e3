#pragma once
// OverlayStateStore: keeps the overlay selection (OverlaySelection::selected() and the mode) in
// the state directory, so the mirror comes back wearing what it wore. The file is small TOML,
// `overlay.toml`:
//
//   # overlay selection, written when a button or the `overlay` command changes it
//   overlay = "top-hat"   # "none" when overlays are off
//   mode = "global"       # or "per_face"
//
// Saving happens in the frame loop (a button press), so it never allocates: paths are built at
// start-up and the text goes into a fixed buffer. Atomic like CardModelStore: temp file, fsync,
// rename, fsync of the folder.

#include "firmware/overlay_selection.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace firmware {

struct OverlayState {
    std::string overlay;  ///< a catalogue name, or "none"
    OverlayMode mode = OverlayMode::Global;
};

class OverlayStateStore {
public:
    /// Longest overlay name that is saved (longer names make save() fail).
    static constexpr std::size_t kMaxNameLength = 128;

    /// Uses `stateDir`, creating it (with parents) if missing. Never throws: a folder that cannot
    /// be made is reported by usable() / lastError() and the selection then just is not kept.
    explicit OverlayStateStore(const std::string& stateDir);

    bool usable() const noexcept { return usable_; }
    const std::string& path() const noexcept { return path_; }
    const char* lastError() const noexcept { return error_; }

    /// Reads the saved state (start-up only). Empty when there is none; `warning` (one line)
    /// says why when the file exists but is unreadable or corrupt: it is then ignored, not
    /// deleted. Whether the name is still in the catalogue is for the caller to check
    /// (OverlaySelection::select(name) returns false).
    std::optional<OverlayState> load(std::string& warning) const;
    /// Writes the state atomically. False on failure (lastError() says why). Never allocates.
    bool save(std::string_view overlay, OverlayMode mode) noexcept;
    /// save(selection.name(selection.selected()), selection.mode()).
    bool save(const OverlaySelection& selection) noexcept;

private:
    std::string dir_;
    std::string path_;
    std::string tempPath_;
    bool usable_ = false;
    char error_[256] = "";
};

}  // namespace firmware
