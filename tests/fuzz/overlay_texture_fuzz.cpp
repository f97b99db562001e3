// An overlay mesh's texture (PNG through libpng), its size checked from the header first.
#include "fuzz_input.hpp"
#include "overlay_texture_file.hpp"  // private to render/src

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string path = fuzz::writeScratchFile("texture.png", data, size);
    try {
        (void)render::readTextureFile(path);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
