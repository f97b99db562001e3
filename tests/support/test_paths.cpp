#include "test_paths.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

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

std::string readFile(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace testing_support
