// A picture file (PNG, JPEG or BMP through OpenCV): the card picture and a frame source's still
// image, read bounded and refused from the header when too large.
#include "fuzz_input.hpp"
#include "platform/image_file.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string path = fuzz::writeScratchFile("picture", data, size);
    try {
        (void)platform::loadImageFile(path, "card picture");
    } catch (const std::runtime_error&) {
    }
    return 0;
}
