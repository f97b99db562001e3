#include "sampling.hpp"

namespace colorlab {

Measurement measureDisc(const vision::ConstImageView& frame, const Sample& sample) noexcept
{
    Measurement m;
    long count = 0;
    double sum[3] = {0.0, 0.0, 0.0};  // B, G, R
    const int r2 = sample.radius * sample.radius;
    for (int dy = -sample.radius; dy <= sample.radius; ++dy) {
        const int y = sample.y + dy;
        if (y < 0 || y >= frame.height) {
            continue;
        }
        const std::uint8_t* row = frame.row(y);
        for (int dx = -sample.radius; dx <= sample.radius; ++dx) {
            const int x = sample.x + dx;
            if (dx * dx + dy * dy > r2 || x < 0 || x >= frame.width) {
                continue;
            }
            const std::uint8_t* p = row + 3 * x;
            for (int c = 0; c < 3; ++c) {
                sum[c] += p[c];
                m.saturated = m.saturated || p[c] == 255;
            }
            ++count;
        }
    }
    if (count > 0) {
        m.b = sum[0] / static_cast<double>(count);
        m.g = sum[1] / static_cast<double>(count);
        m.r = sum[2] / static_cast<double>(count);
    }
    return m;
}

bool Recording::rowSaturated(std::size_t row) const noexcept
{
    for (const Measurement& m : measurements[row]) {
        if (m.saturated) {
            return true;
        }
    }
    return false;
}

}  // namespace colorlab
