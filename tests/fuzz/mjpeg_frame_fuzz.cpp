// A frame from an MJPEG camera (libjpeg-turbo into the preallocated 64x48 image): any bytes are
// decoded or refused with lastError(), never a crash.
#include "fuzz_input.hpp"
#include "platform/mjpeg_decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static platform::MjpegDecoder decoder(64, 48);
    (void)decoder.decode(data, size);
    return 0;
}
