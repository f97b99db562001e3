#pragma once
// A Console for tests: scripted input, output captured into a fixed buffer (no allocation, so it
// can run inside the allocation-counting scope).

#include "platform/console.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>

class FakeConsole final : public platform::Console {
public:
    const char* description() const noexcept override { return "fake"; }
    long read(char* buffer, std::size_t capacity) noexcept override
    {
        const std::size_t n = std::min(capacity, pendingLength_ - pendingOffset_);
        std::memcpy(buffer, pending_ + pendingOffset_, n);
        pendingOffset_ += n;
        return static_cast<long>(n);
    }
    void write(std::string_view text) noexcept override
    {
        const std::size_t n = std::min(text.size(), sizeof output_ - 1 - outputLength_);
        std::memcpy(output_ + outputLength_, text.data(), n);
        outputLength_ += n;
        output_[outputLength_] = '\0';
    }
    /// Queues input (the text must outlive the reads).
    void type(const char* text) noexcept
    {
        pending_ = text;
        pendingLength_ = std::strlen(text);
        pendingOffset_ = 0;
    }
    std::string_view output() const noexcept { return {output_, outputLength_}; }
    void clearOutput() noexcept
    {
        outputLength_ = 0;
        output_[0] = '\0';
    }

private:
    const char* pending_ = "";
    std::size_t pendingLength_ = 0;
    std::size_t pendingOffset_ = 0;
    char output_[64 * 1024] = "";
    std::size_t outputLength_ = 0;
};
