// The overlay catalogue (TOML): the input is catalogue.toml in a folder that also holds the test
// hat and glasses (OBJ) and a PNG, so a catalogue naming them reaches the mesh and texture loading.
#include "fuzz_input.hpp"
#include "render/overlay_catalogue.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const bool assets = [] {
        fuzz::copyIntoScratch("tests/data/overlays/test_hat.obj", "test_hat.obj");
        fuzz::copyIntoScratch("tests/data/overlays/test_glasses.obj", "test_glasses.obj");
        fuzz::copyIntoScratch("tests/fuzz/seeds/images/hat-16x20.png", "texture.png");
        return true;
    }();
    (void)assets;
    const std::string path = fuzz::writeScratchFile("catalogue.toml", data, size);
    try {
        (void)render::OverlayCatalogue::load(path);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
