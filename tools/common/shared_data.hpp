#pragma once
// Where the tools find the real data we did not make (../shared/data beside the project: IMM,
// FGNet, CANDIDE-3, photographs; each folder has a SOURCE.txt). The tools used to look only
// relative to the working directory, so run from anywhere but the project root they silently
// used other backgrounds (cardgen) or failed on a missing file far from the cause.

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace tool_data {

/// The shared data folder a tool uses unless `--data` says otherwise: $MIRROR_DATA_DIR when set;
/// else `../shared/data` from the working directory when it is there (the project root: the
/// paths tools print stay short); else the one beside the project the program was built in
/// (PROJECT/build/bin/TOOL -> PROJECT/../shared/data); else `../shared/data`, which the tool's
/// check then reports as missing.
inline std::string defaultDir()
{
    namespace fs = std::filesystem;
    if (const char* env = std::getenv("MIRROR_DATA_DIR"); env && *env)
        return env;
    const std::string relative = "../shared/data";
    std::error_code ec;
    if (fs::is_directory(relative, ec))
        return relative;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path beside = exe.parent_path().parent_path().parent_path().parent_path() /
                                "shared" / "data";
        if (fs::is_directory(beside, ec))
            return beside.lexically_normal().string();
    }
    return relative;
}

/// Empty when DIR is a folder; else one line for the tool to print: what is missing and how to
/// point at it.
inline std::string missingReason(const std::string& dir)
{
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec))
        return {};
    return "no shared data folder at '" + dir +
           "' (give --data DIR or set MIRROR_DATA_DIR; the project looks for ../shared/data "
           "beside itself)";
}

}  // namespace tool_data
