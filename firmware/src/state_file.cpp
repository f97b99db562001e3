#include "state_file.hpp"

#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

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
    const vision::BoundedFile file = vision::readBoundedFile(path, vision::limits::kStateFileBytes);
    if (file.status == vision::BoundedFile::Status::Missing)
        return std::nullopt;
    if (file.status != vision::BoundedFile::Status::Ok) {
        warning = path + ": " + file.problem + "; ignored";
        return std::nullopt;
    }
    try {
        return toml::parse(file.text, path);
    } catch (const toml::parse_error& e) {
        warning = path + ":" + std::to_string(e.source().begin.line) + ":" +
                  std::to_string(e.source().begin.column) + ": " + std::string(e.description()) +
                  "; ignored";
        return std::nullopt;
    }
}

}  // namespace firmware
