// The config file (TOML + the schema): any text is a Config or a ConfigError, never a crash; a
// Config written back with toToml parses again (the file `mirror --print-config` writes).
#include "firmware/config.hpp"
#include "fuzz_input.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    firmware::Config config;
    try {
        config = firmware::parseConfig(std::string(fuzz::text(data, size)), "fuzz.toml");
    } catch (const firmware::ConfigError&) {
        return 0;
    }
    try {
        (void)firmware::parseConfig(firmware::toToml(config), "round-trip.toml");
    } catch (const firmware::ConfigError&) {
        std::abort();  // what was accepted must be written back loadable
    }
    return 0;
}
