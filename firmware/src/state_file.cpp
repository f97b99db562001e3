#include "state_file.hpp"

#include <cstdio>
#include <filesystem>

namespace firmware {

bool createStateFolder(const std::string& dir, char* error, std::size_t errorCapacity)
{
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        std::snprintf(error, errorCapacity, "state folder %s: %s", dir.c_str(),
                      ec.message().c_str());
        return false;
    }
    return true;
}

std::optional<toml::table> readStateToml(const std::string& path, std::string& warning)
{
    warning.clear();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        return std::nullopt;
    try {
        return toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        warning = path + ":" + std::to_string(e.source().begin.line) + ":" +
                  std::to_string(e.source().begin.column) + ": " + std::string(e.description()) +
                  "; ignored";
        return std::nullopt;
    }
}

}  // namespace firmware
