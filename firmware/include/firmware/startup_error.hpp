#pragma once
// StartupError: a failure before the first frame, with the process exit code it maps to.
// Thrown by the factories and caught once in main, which prints one line and exits.

#include <stdexcept>
#include <string>

namespace firmware {

class StartupError : public std::runtime_error {
public:
    StartupError(int exitCode, const std::string& message)
        : std::runtime_error(message), exitCode_(exitCode)
    {
    }
    int exitCode() const noexcept { return exitCode_; }

private:
    int exitCode_;
};

}  // namespace firmware
