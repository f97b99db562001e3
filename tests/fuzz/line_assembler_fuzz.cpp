// The console's line assembly: bytes in chunks of any size become lines of printable ASCII no
// longer than the maximum, whatever the bytes are. The first byte sets the maximum line length,
// the second the chunk size.
#include "firmware/line_assembler.hpp"
#include "fuzz_input.hpp"

#include <algorithm>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 2)
        return 0;
    const std::size_t maxLine = 1 + data[0];
    const std::size_t chunk = 1 + data[1];
    data += 2;
    size -= 2;
    firmware::LineAssembler assembler(maxLine);
    const auto check = [&](const firmware::LineEvent& event) {
        if (event.kind != firmware::LineEventKind::Line)
            return;
        if (event.text.empty() || event.text.size() > maxLine)
            std::abort();
        for (const char c : event.text)
            if (c < 0x20 || c > 0x7E)
                std::abort();
    };
    for (std::size_t at = 0; at < size; at += chunk) {
        assembler.feed(reinterpret_cast<const char*>(data) + at, std::min(chunk, size - at), check);
        if (assembler.pendingLength() > maxLine)
            std::abort();
    }
    assembler.finish(check);
    return 0;
}
