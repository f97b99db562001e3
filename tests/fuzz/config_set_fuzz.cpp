// `--set KEY=VALUE` overrides: the input is up to four of them, separated by NUL bytes (argv
// cannot hold a NUL), applied over the defaults with no config file.
#include "firmware/config.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    firmware::ConfigRequest request;
    request.path = "/nonexistent/fuzz/mirror.toml";  // missing without --config: the defaults
    std::string_view rest = fuzz::text(data, size);
    while (request.sets.size() < 4) {
        const auto end = rest.find('\0');
        request.sets.emplace_back(rest.substr(0, end));
        if (end == std::string_view::npos)
            break;
        rest.remove_prefix(end + 1);
    }
    try {
        (void)firmware::loadConfig(request);
    } catch (const firmware::ConfigError&) {
    }
    return 0;
}
