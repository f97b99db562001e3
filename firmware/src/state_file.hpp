#pragma once
// What every small state file of the mirror (the trained card colour, the overlay choice) does
// the same way: its folder is made at start-up, and reading it back is TOML whose syntax errors
// become one warning line ("PATH:LINE:COLUMN: what; ignored") so a corrupt file is skipped, not
// fatal. Writing goes through writeFileAtomically (atomic_file.hpp).

#include <toml++/toml.h>

#include <cstddef>
#include <optional>
#include <string>

namespace firmware {

/// Creates `dir` (and its parents). False with "state folder DIR: why" in `error` when it cannot.
bool createStateFolder(const std::string& dir, char* error, std::size_t errorCapacity);

/// The TOML table in `path`; nothing when the file does not exist (warning empty) or does not
/// parse (warning set).
std::optional<toml::table> readStateToml(const std::string& path, std::string& warning);

}  // namespace firmware
