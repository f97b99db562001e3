// A person's file in the state folder (people/NAME.toml, PersonStore): any file is a person or
// one warning, never a crash.
#include "firmware/person_store.hpp"
#include "fuzz_input.hpp"

#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    // The seeds' model (crc32:11e58ce4), so a well-formed input reaches every field.
    static const firmware::PersonStore store(fuzz::scratchFolder(), 0x11e58ce4);
    fuzz::writeScratchFile("people/anna.toml", data, size);
    std::vector<std::string> warnings;
    (void)store.loadAll(warnings);
    return 0;
}
