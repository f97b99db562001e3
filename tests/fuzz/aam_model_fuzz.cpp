// The AAM model file the runtime loads: any bytes are a model or one problem line. Each input is
// decoded twice: as it is, and with its header made right (magic, version, payload size and
// CRC-32), so mutations reach the payload's parser instead of stopping at the checksum. A model
// that decodes is encoded and decoded again: what is read must be writable.
#include "crc32.hpp"  // private to vision/src
#include "fuzz_input.hpp"
#include "vision/aam_model.hpp"

#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

void decodeAndRewrite(std::span<const std::byte> bytes)
{
    const vision::AamModelFile file = vision::decodeAamModel(bytes);
    if (!file.ok)
        return;
    std::string again;
    try {
        again = vision::encodeAamModel(file.model);
    } catch (const std::invalid_argument&) {
        std::abort();
    }
    if (!vision::decodeAamModel(std::as_bytes(std::span(again.data(), again.size()))).ok)
        std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    decodeAndRewrite(std::as_bytes(std::span(data, size)));
    constexpr std::size_t kHeader = 20;
    if (size < kHeader)
        return 0;
    std::vector<std::byte> fixed(reinterpret_cast<const std::byte*>(data),
                                 reinterpret_cast<const std::byte*>(data) + size);
    const std::uint32_t version = vision::kAamModelVersion;
    const auto payloadSize = static_cast<std::uint32_t>(size - kHeader);
    const std::uint32_t sum = vision::crc32(std::span(fixed).subspan(kHeader));
    std::memcpy(fixed.data(), vision::kAamModelMagic, 8);
    std::memcpy(fixed.data() + 8, &version, 4);  // the file is little-endian, as is every target
    std::memcpy(fixed.data() + 12, &payloadSize, 4);
    std::memcpy(fixed.data() + 16, &sum, 4);
    decodeAndRewrite(fixed);
    return 0;
}
