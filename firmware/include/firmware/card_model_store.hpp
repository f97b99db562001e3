#pragma once
// CardModelStore: keeps the trained card colour (vision::CardColorModel) in the state directory, so
// a card trained once is found again after a restart. The file is small TOML, `card-model.toml`:
//
//   # trained card colour (chromaticity, 0..255)
//   mean = [92.1, 121.4, 41.5]
//   sigma = [3.2, 2.9, 2.4]
//
// Saving happens in the frame loop (console `card train`), so it never allocates: the paths are
// built here at start-up and the text goes into a fixed buffer. It is atomic: temp file, fsync,
// rename, fsync of the folder; a crash leaves the old file or the new one, never half of one.

#include "vision/card_tracker.hpp"

#include <optional>
#include <string>

namespace firmware {

class CardModelStore {
public:
    /// Uses `stateDir`, creating it (with parents) if missing. Never throws: a folder that cannot
    /// be made is reported by usable() / lastError() and training then works without being kept.
    explicit CardModelStore(const std::string& stateDir);

    bool usable() const noexcept { return usable_; }
    const std::string& path() const noexcept { return path_; }
    const char* lastError() const noexcept { return error_; }

    /// Reads the saved model (start-up only). Empty when there is none; `warning` says why when the
    /// file exists but is unreadable or corrupt (it is then ignored, not deleted).
    std::optional<vision::CardColorModel> load(std::string& warning) const;
    /// Writes the model atomically. False on failure, lastError() says why. Never allocates.
    bool save(const vision::CardColorModel& model) noexcept;
    /// Deletes the saved model (`card forget`); a file already absent is no error. False on
    /// failure, lastError() says why.
    bool remove() noexcept;

private:
    std::string dir_;
    std::string path_;
    std::string tempPath_;
    bool usable_ = false;
    char error_[256] = "";
};

}  // namespace firmware
