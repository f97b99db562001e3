// The landmark files of the AAM's training images: every input is read both as an IMM .asf and
// as a .pts; each gives points or one AnnotationError line.
#include "annotation_files.hpp"  // tools/aam
#include "fuzz_input.hpp"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(fuzz::text(data, size));
    try {
        std::istringstream in(text);
        (void)aam::readAsf(in, "fuzz.asf");
    } catch (const aam::AnnotationError&) {
    }
    try {
        std::istringstream in(text);
        (void)aam::readPts(in, "fuzz.pts");
    } catch (const aam::AnnotationError&) {
    }
    return 0;
}
