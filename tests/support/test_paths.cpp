#include "test_paths.hpp"

#include <filesystem>

namespace testing_support {

std::string sourceDir()
{
    return MIRROR_SOURCE_DIR;
}
std::string binaryDir()
{
    return MIRROR_BINARY_DIR;
}

std::string sharedData(const std::string& relative)
{
    return (std::filesystem::path(MIRROR_SOURCE_DIR) / ".." / "shared" / "data" / relative)
        .lexically_normal()
        .string();
}

std::string freshOutputDir(const std::string& name)
{
    const auto dir = std::filesystem::path(MIRROR_BINARY_DIR) / "test-output" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

}  // namespace testing_support
