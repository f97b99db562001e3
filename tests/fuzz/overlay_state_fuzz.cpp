// The overlay choice kept in the state folder (overlay.toml): any file is a state or one warning.
#include "firmware/overlay_state_store.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const firmware::OverlayStateStore store(fuzz::scratchFolder());
    fuzz::writeScratchFile("overlay.toml", data, size);
    std::string warning;
    (void)store.load(warning);
    return 0;
}
