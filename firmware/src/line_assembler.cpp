#include "firmware/line_assembler.hpp"

#include <stdexcept>

namespace firmware {

LineAssembler::LineAssembler(std::size_t maxLineLength) : capacity_(maxLineLength)
{
    if (maxLineLength == 0)
        throw std::runtime_error("line assembler: the maximum line length must be at least 1");
    buffer_ = std::make_unique<char[]>(maxLineLength);
}

void LineAssembler::reset() noexcept
{
    length_ = 0;
    discarding_ = false;
}

bool LineAssembler::endLine(LineEvent& event) noexcept
{
    const bool deliver = !discarding_ && length_ > 0;
    const std::size_t length = length_;
    reset();
    if (deliver)
        event = {LineEventKind::Line, std::string_view(buffer_.get(), length)};
    return deliver;
}

bool LineAssembler::scan(const char*& data, std::size_t& size, LineEvent& event) noexcept
{
    while (size > 0) {
        if (discarding_) {
            // Skip the rest of a rejected line without per-byte bookkeeping.
            while (size > 0 && *data != '\r' && *data != '\n') {
                ++data;
                --size;
            }
            if (size == 0)
                return false;
        }
        const auto c = static_cast<unsigned char>(*data);
        ++data;
        --size;
        if (c == '\r' || c == '\n') {
            if (endLine(event))
                return true;
            continue;
        }
        if (c == 0x08 || c == 0x7F) {
            if (length_ > 0)
                --length_;
            continue;
        }
        char ch;
        if (c == '\t') {
            ch = ' ';
        } else if (c >= 0x20 && c <= 0x7E) {
            ch = static_cast<char>(c);
        } else {
            discarding_ = true;
            event = {LineEventKind::Binary, {}};
            return true;
        }
        if (length_ == capacity_) {
            discarding_ = true;
            event = {LineEventKind::TooLong, {}};
            return true;
        }
        buffer_[length_++] = ch;
    }
    return false;
}

}  // namespace firmware
