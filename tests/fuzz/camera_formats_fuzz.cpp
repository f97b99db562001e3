// Camera format negotiation: whatever four-character codes a camera (libcamera or V4L2) offers,
// in any order or number, one supported format or none is chosen, and every code can be named.
// The input is the offered codes (4 bytes each); its first byte also orders the preference.
#include "fuzz_input.hpp"
#include "platform/camera_formats.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::vector<std::uint32_t> offered(size / 4);
    if (!offered.empty())
        std::memcpy(offered.data(), data, offered.size() * 4);
    std::vector<vision::PixelFormat> preference = platform::defaultFormatPreference();
    if (size > 0)
        std::rotate(preference.begin(), preference.begin() + data[0] % preference.size(),
                    preference.end());
    for (const std::uint32_t code : offered) {
        char name[11];
        if (std::strlen(platform::fourccName(code, name, sizeof name)) >= sizeof name)
            std::abort();
        (void)platform::pixelFormatFromLibcamera(code);
        (void)platform::pixelFormatFromV4l2(code);
    }
    const auto libcamera = platform::chooseLibcameraFormat(offered, preference);
    if (libcamera &&
        std::find(preference.begin(), preference.end(), *libcamera) == preference.end())
        std::abort();
    for (const bool mjpeg : {false, true}) {
        const auto v4l2 = platform::chooseV4l2Format(offered, preference, mjpeg);
        if (v4l2 && std::find(offered.begin(), offered.end(), v4l2->fourcc) == offered.end())
            std::abort();
    }
    return 0;
}
