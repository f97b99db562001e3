#pragma once
// What the harnesses share: the libFuzzer entry point's signature, and for loaders that take a
// path, the input written to a file in this process's own temporary folder (docs/FUZZING.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fuzz {

/// The input as text (the bytes unchanged, NUL and all).
inline std::string_view text(const std::uint8_t* data, std::size_t size)
{
    return {reinterpret_cast<const char*>(data), size};
}

/// This process's temporary folder (made on first use, removed at exit).
const std::string& scratchFolder();

/// Writes the input to `scratchFolder()/name` (replacing it) and returns that path.
std::string writeScratchFile(const std::string& name, const std::uint8_t* data, std::size_t size);

/// Copies a file of the source tree (MIRROR_SOURCE_DIR/relative) into the scratch folder, so a
/// fuzzed file can name it (a catalogue its OBJ, for instance).
void copyIntoScratch(const std::string& relative, const std::string& name);

}  // namespace fuzz
