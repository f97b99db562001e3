// The CANDIDE face definition (.wfm) aam-build reads: any text is a mesh or one WfmError line.
#include "fuzz_input.hpp"
#include "wfm_reader.hpp"  // tools/aam

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::istringstream in{std::string(fuzz::text(data, size))};
    try {
        (void)aam::readWfm(in, "fuzz.wfm");
    } catch (const aam::WfmError&) {
    }
    return 0;
}
