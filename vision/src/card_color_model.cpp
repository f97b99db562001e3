#include "vision/card_color_model.hpp"

#include "color_bands.hpp"

#include <algorithm>
#include <cmath>

namespace vision {

namespace {

bool planesValid(const ChromaticityPlanes& c) noexcept
{
    return !c.r.empty() && !c.g.empty() && !c.b.empty() && c.r.size() == c.g.size() &&
           c.r.size() == c.b.size();
}

/// Integer sums of one channel: exact for any frame up to 2^32 pixels.
struct Moments {
    std::uint64_t sum[3] = {0, 0, 0};
    std::uint64_t sumSq[3] = {0, 0, 0};
    std::uint64_t n = 0;

    void add(std::uint8_t r, std::uint8_t g, std::uint8_t b) noexcept
    {
        sum[0] += r;
        sum[1] += g;
        sum[2] += b;
        sumSq[0] += static_cast<std::uint32_t>(r) * r;
        sumSq[1] += static_cast<std::uint32_t>(g) * g;
        sumSq[2] += static_cast<std::uint32_t>(b) * b;
        ++n;
    }

    CardColorModel model(float minSigma) const noexcept
    {
        CardColorModel m;
        const double inv = 1.0 / static_cast<double>(n);
        for (int c = 0; c < 3; ++c) {
            const double mean = static_cast<double>(sum[c]) * inv;
            const double var = std::max(0.0, static_cast<double>(sumSq[c]) * inv - mean * mean);
            m.mean[c] = static_cast<float>(mean);
            m.sigma[c] = std::max(minSigma, static_cast<float>(std::sqrt(var)));
        }
        m.valid = true;
        return m;
    }
};

}  // namespace

ColorBounds colorBounds(const CardColorModel& model, float t) noexcept
{
    ColorBounds b;
    if (!model.valid)
        return b;  // lo > hi: nothing matches
    for (int c = 0; c < 3; ++c) {
        const float half = t * model.sigma[c];
        // x > mu - ts  <=>  x >= floor(mu - ts) + 1;  x < mu + ts  <=>  x <= ceil(mu + ts) - 1.
        const float lo = std::floor(model.mean[c] - half) + 1.f;
        const float hi = std::ceil(model.mean[c] + half) - 1.f;
        if (!(hi >= lo) || hi < 0.f || lo > 255.f) {
            b.lo[c] = 1;
            b.hi[c] = 0;
            continue;
        }
        b.lo[c] = static_cast<std::uint8_t>(std::clamp(lo, 0.f, 255.f));
        b.hi[c] = static_cast<std::uint8_t>(std::clamp(hi, 0.f, 255.f));
    }
    return b;
}

ColorBounds joinedBounds(const ColorBounds& a, const ColorBounds& b) noexcept
{
    ColorBounds out;
    for (int c = 0; c < 3; ++c) {
        const bool aEmpty = a.lo[c] > a.hi[c], bEmpty = b.lo[c] > b.hi[c];
        if (aEmpty || bEmpty) {
            out.lo[c] = aEmpty ? b.lo[c] : a.lo[c];
            out.hi[c] = aEmpty ? b.hi[c] : a.hi[c];
            continue;
        }
        out.lo[c] = std::min(a.lo[c], b.lo[c]);
        out.hi[c] = std::max(a.hi[c], b.hi[c]);
    }
    return out;
}

bool trainColorModel(const ChromaticityPlanes& chroma, Rect region, float minSigma,
                     CardColorModel& out) noexcept
{
    if (!planesValid(chroma))
        return false;
    const Rect r = clipped(region, chroma.r.width, chroma.r.height);
    if (r.width <= 0 || r.height <= 0)
        return false;
    Moments m;
    for (int y = r.y; y < r.y + r.height; ++y) {
        const std::uint8_t* pr = chroma.r.row(y);
        const std::uint8_t* pg = chroma.g.row(y);
        const std::uint8_t* pb = chroma.b.row(y);
        for (int x = r.x; x < r.x + r.width; ++x)
            m.add(pr[x], pg[x], pb[x]);
    }
    out = m.model(minSigma);
    return true;
}

bool measureColorModel(const ChromaticityPlanes& chroma, const ConstImageView& mask, Rect region,
                       int step, float minSigma, int minPixels, CardColorModel& out) noexcept
{
    if (!planesValid(chroma) || mask.empty() || mask.size() != chroma.r.size())
        return false;
    const Rect r = clipped(region, chroma.r.width, chroma.r.height);
    if (r.width <= 0 || r.height <= 0)
        return false;
    step = std::max(step, 1);
    Moments m;
    for (int y = r.y; y < r.y + r.height; y += step) {
        const std::uint8_t* pm = mask.row(y);
        const std::uint8_t* pr = chroma.r.row(y);
        const std::uint8_t* pg = chroma.g.row(y);
        const std::uint8_t* pb = chroma.b.row(y);
        for (int x = r.x; x < r.x + r.width; x += step)
            if (pm[x])
                m.add(pr[x], pg[x], pb[x]);
    }
    if (m.n < static_cast<std::uint64_t>(std::max(minPixels, 1)))
        return false;
    out = m.model(minSigma);
    return true;
}

CardColorModel blendColorModel(const CardColorModel& trained, const CardColorModel& previous,
                               const CardColorModel& current, float alpha, float beta) noexcept
{
    if (!trained.valid)
        return trained;
    const CardColorModel& prev = previous.valid ? previous : trained;
    const CardColorModel& cur = current.valid ? current : prev;
    const float a = std::clamp(alpha, 0.f, 1.f);
    const float b = std::clamp(beta, 0.f, 1.f);
    CardColorModel out;
    for (int c = 0; c < 3; ++c) {
        out.mean[c] =
            a * trained.mean[c] + (1.f - a) * (b * prev.mean[c] + (1.f - b) * cur.mean[c]);
        out.sigma[c] =
            a * trained.sigma[c] + (1.f - a) * (b * prev.sigma[c] + (1.f - b) * cur.sigma[c]);
    }
    out.valid = true;
    return out;
}

void colorTest(const ChromaticityPlanes& chroma, const ColorBounds& bounds, Rect region,
               const ImageView& mask) noexcept
{
    if (!planesValid(chroma) || mask.empty() || mask.size() != chroma.r.size())
        return;
    const Rect r = clipped(region, chroma.r.width, chroma.r.height);
    // matchesColor without branches, so that the row loop vectorises (16 pixels a step on NEON).
    const ColorBands bands = bandsOf(bounds);
    for (int y = r.y; y < r.y + r.height; ++y) {
        const std::uint8_t* __restrict pr = chroma.r.row(y);
        const std::uint8_t* __restrict pg = chroma.g.row(y);
        const std::uint8_t* __restrict pb = chroma.b.row(y);
        std::uint8_t* __restrict pm = mask.row(y);
        for (int x = r.x; x < r.x + r.width; ++x)
            pm[x] = matchMask(bands, pr[x], pg[x], pb[x]);
    }
}

float colorFit(const CardColorModel& model, const CardColorModel& sample, float t) noexcept
{
    if (!model.valid || !sample.valid || t <= 0.f)
        return 0.f;
    float worst = 0.f;
    for (int c = 0; c < 3; ++c) {
        const float d = std::fabs(sample.mean[c] - model.mean[c]) / (t * model.sigma[c]);
        worst = std::max(worst, d);
    }
    return std::clamp(1.f - worst, 0.f, 1.f);
}

}  // namespace vision
