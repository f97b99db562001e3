// The fitted face's texture descriptor (aam_texture.hpp).
//
// Why these choices:
//  - Uniform local binary patterns compare each pixel with its neighbours only: any monotonic
//    change of the grey levels (IMM's side light, a camera's gain) leaves them as they are, which
//    the appearance parameters (gain and bias removed, but projected on a few modes) are not.
//  - On the mean-shape frame: the fitted shape has already put the eyes, nose and mouth in the
//    same cells for every face and pose the fit holds, so cells compare like with like.
//  - Only model pixels whose 8 neighbours were all warped count (a frame pixel outside every span
//    was never sampled).
#include "aam_texture.hpp"

#include <algorithm>
#include <cmath>

namespace vision::aam {

namespace {

constexpr int kDx[8] = {-1, 0, 1, 1, 1, 0, -1, -1};
constexpr int kDy[8] = {-1, -1, -1, 0, 1, 1, 1, 0};

std::array<std::uint8_t, 256> makeUniformBins() noexcept
{
    std::array<std::uint8_t, 256> bins{};
    int next = 0;
    for (int code = 0; code < 256; ++code) {
        int transitions = 0;
        for (int b = 0; b < 8; ++b)
            transitions += ((code >> b) & 1) != ((code >> ((b + 1) % 8)) & 1) ? 1 : 0;
        bins[static_cast<std::size_t>(code)] =
            static_cast<std::uint8_t>(transitions <= 2 ? next++ : kAamLbpBins - 1);
    }
    return bins;
}

}  // namespace

const std::array<std::uint8_t, 256>& uniformPatternBins() noexcept
{
    static const std::array<std::uint8_t, 256> bins = makeUniformBins();
    return bins;
}

TextureLayout textureLayout(const Tables& t, int grid)
{
    TextureLayout layout;
    if (grid <= 0 || t.runs.empty())
        return layout;
    grid = std::min(grid, kAamMaxTextureGrid);
    for (const WarpRun& r : t.runs) {
        layout.width = std::max(layout.width, r.x0 + r.count);
        layout.height = std::max(layout.height, r.y + 1);
    }
    const auto pixels = static_cast<std::size_t>(layout.width) * layout.height;
    std::vector<bool> sampled(pixels, false), model(pixels, false);
    layout.frameOfSpan.assign(static_cast<std::size_t>(t.spanPixels), 0);
    int x0 = layout.width, x1 = -1, y0 = layout.height, y1 = -1;
    for (const WarpRun& r : t.runs)
        for (int k = 0; k < r.count; ++k) {
            const int x = r.x0 + k, span = static_cast<int>(r.offset) + k;
            const auto at = static_cast<std::size_t>(r.y) * layout.width + x;
            layout.frameOfSpan[static_cast<std::size_t>(span)] = static_cast<std::int32_t>(at);
            sampled[at] = true;
            if (t.mask[static_cast<std::size_t>(span)] != 0) {
                model[at] = true;
                x0 = std::min(x0, x);
                x1 = std::max(x1, x);
                y0 = std::min(y0, static_cast<int>(r.y));
                y1 = std::max(y1, static_cast<int>(r.y));
            }
        }
    layout.grid = grid;
    layout.cells = grid * grid;
    layout.cellOf.assign(pixels, kNoCell);
    layout.cellPixels.assign(static_cast<std::size_t>(layout.cells), 0);
    if (x1 < x0)
        return layout;
    for (int y = 1; y + 1 < layout.height; ++y)
        for (int x = 1; x + 1 < layout.width; ++x) {
            const auto at = static_cast<std::size_t>(y) * layout.width + x;
            if (!model[at])
                continue;
            bool all = true;
            for (int n = 0; n < 8; ++n)
                all = all && sampled[at + static_cast<std::size_t>(kDy[n] * layout.width + kDx[n])];
            if (!all)
                continue;
            const int cx = (x - x0) * grid / (x1 - x0 + 1), cy = (y - y0) * grid / (y1 - y0 + 1);
            const int cell = cy * grid + cx;
            layout.cellOf[at] = static_cast<std::uint8_t>(cell);
            ++layout.cellPixels[static_cast<std::size_t>(cell)];
        }
    return layout;
}

int textureOf(const TextureLayout& layout, const std::int16_t* warped, std::int16_t* frame,
              std::uint16_t* histogram, std::span<std::uint8_t> out) noexcept
{
    const int bins = layout.bins();
    if (bins == 0 || out.size() < static_cast<std::size_t>(bins))
        return 0;
    const std::size_t span = layout.frameOfSpan.size();
    for (std::size_t i = 0; i < span; ++i)
        frame[layout.frameOfSpan[i]] = warped[i];
    std::fill(histogram, histogram + bins, std::uint16_t{0});
    const auto& uniform = uniformPatternBins();
    const int w = layout.width;
    const std::ptrdiff_t offsets[8] = {-w - 1, -w, -w + 1, 1, w + 1, w, w - 1, -1};
    const std::uint8_t* cellOf = layout.cellOf.data();
    for (int y = 1; y + 1 < layout.height; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * w;
        for (int x = 1; x + 1 < w; ++x) {
            const std::size_t at = row + static_cast<std::size_t>(x);
            const std::uint8_t cell = cellOf[at];
            if (cell == kNoCell)
                continue;
            const std::int16_t* p = frame + at;
            const std::int16_t c = *p;
            unsigned code = 0;
            // Written as a branch on widened values: GCC 12 at -O1 with the sanitizers built
            // `code |= (p[o] >= c ? 1u : 0u) << n` as all ones (the ASan build's test caught it).
            for (int n = 0; n < 8; ++n)
                if (static_cast<int>(p[offsets[n]]) >= static_cast<int>(c))
                    code |= 1u << n;
            ++histogram[cell * kAamLbpBins + uniform[code]];
        }
    }
    for (int cell = 0; cell < layout.cells; ++cell) {
        const float total = std::max<float>(layout.cellPixels[static_cast<std::size_t>(cell)], 1.f);
        for (int b = 0; b < kAamLbpBins; ++b) {
            const int i = cell * kAamLbpBins + b;
            out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(
                std::lround(255.f * std::sqrt(static_cast<float>(histogram[i]) / total)));
        }
    }
    return bins;
}

}  // namespace vision::aam
