// The size check from a PNG, JPEG or BMP header alone, before any decoder runs: the allocation-free
// frame-loop check and the one that says why must agree.
#include "fuzz_input.hpp"
#include "image_header.hpp"  // private to platform/src

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    (void)platform::imageHeaderSize(data, size);
    const bool within = platform::imageHeaderWithinLimits(data, size);
    const std::string problem = platform::checkImageHeader(data, size);
    if (within != problem.empty())
        std::abort();
    return 0;
}
