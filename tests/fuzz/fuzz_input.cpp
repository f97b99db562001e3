// The scratch folder of the path-taking harnesses: one per process under $TMPDIR, so harnesses
// running side by side never share a file.
#include "fuzz_input.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fuzz {

namespace {

std::string makeFolder()
{
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern =
        std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/fuzz-XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr)
        throw std::runtime_error("cannot make a scratch folder from " + pattern);
    return pattern;
}

struct Folder {
    std::string path = makeFolder();
    ~Folder()
    {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
};

}  // namespace

const std::string& scratchFolder()
{
    static const Folder folder;
    return folder.path;
}

std::string writeScratchFile(const std::string& name, const std::uint8_t* data, std::size_t size)
{
    const std::string path = scratchFolder() + "/" + name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out)
        throw std::runtime_error("cannot write " + path);
    return path;
}

void copyIntoScratch(const std::string& relative, const std::string& name)
{
    std::filesystem::copy_file(std::string(MIRROR_SOURCE_DIR) + "/" + relative,
                               scratchFolder() + "/" + name,
                               std::filesystem::copy_options::overwrite_existing);
}

}  // namespace fuzz
