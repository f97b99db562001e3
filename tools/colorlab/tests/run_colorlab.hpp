#pragma once
// Runs the colorlab binary for the command-line tests and captures what it prints.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace colorlab_test {

struct RunResult {
    int exitCode = -1;
    std::string output;  ///< stdout and stderr together
};

/// `args` is appended to the binary's path as shell words (quote them yourself).
inline RunResult runColorlab(const std::string& args, const std::string& workDir = "")
{
    std::string command = std::string("'") + COLORLAB_EXE + "' " + args + " 2>&1";
    if (!workDir.empty()) {
        command = "cd '" + workDir + "' && " + command;
    }
    RunResult result;
    std::FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> buffer{};
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
        result.output.append(buffer.data(), n);
    }
    const int status = ::pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

}  // namespace colorlab_test
