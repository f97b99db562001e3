// The face cascade (OpenCV's cascade XML): any text is a HaarCascade or one runtime_error line.
#include "fuzz_input.hpp"
#include "vision/haar_cascade.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        (void)vision::parseHaarCascade(fuzz::text(data, size), "fuzz.xml");
    } catch (const std::runtime_error&) {
    }
    return 0;
}
