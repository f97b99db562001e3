#include "vision/edge_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace vision {

namespace {

constexpr int kMaxWalk = 160;
constexpr int kMaxBand = 4;

/// Pixel (x, y) through the deinterlacing rule of §2 (dissertation 4.2.4), per channel: on an odd
/// row, a value that differs from the even rows' above and below more than they differ from each
/// other is the previous field (tearing) and is replaced by their mean; static detail keeps its own
/// value.
void fieldPixel(const ConstImageView& rgb, int bpp, int x, int y, std::uint8_t out[3]) noexcept
{
    const std::ptrdiff_t off = static_cast<std::ptrdiff_t>(x) * bpp;
    const std::uint8_t* p = rgb.row(y) + off;
    if ((y & 1) == 0 || y + 1 >= rgb.height) {
        out[0] = p[0];
        out[1] = p[1];
        out[2] = p[2];
        return;
    }
    const std::uint8_t* a = rgb.row(y - 1) + off;
    const std::uint8_t* b = rgb.row(y + 1) + off;
    for (int c = 0; c < 3; ++c)
        out[c] = std::abs(b[c] - a[c]) < std::abs(p[c] - a[c])
                     ? static_cast<std::uint8_t>((a[c] + b[c] + 1) / 2)
                     : p[c];
}

/// Below this sum of R, G and B (per pixel) chromaticity is too noisy to mark an edge.
constexpr int kChromaticityDarkSum = 3 * 40;

/// Chromaticity of a band-mean colour (1/16 units), 0..4080 per channel: 16 * 255 c / sum; -1 in
/// the first channel when the colour is too dark for its chromaticity to mean anything.
void chromaticityOf(const int col[3], int out[3]) noexcept
{
    const int sum = col[0] + col[1] + col[2];
    if (sum < 16 * kChromaticityDarkSum) {
        out[0] = -1;
        out[1] = out[2] = 0;
        return;
    }
    for (int c = 0; c < 3; ++c)
        out[c] = (4080 * col[c] + sum / 2) / sum;
}

/// How strong the step from walk position k to k + 1 is, in units of the thresholds (1024 = at a
/// threshold): the larger of the saturation step and the chromaticity step.
int stepStrength(const int* s, const int (*ch)[3], int k, int thresholdS, int thresholdC) noexcept
{
    const int ds = std::abs(s[k + 1] - s[k]) * 1024 / thresholdS;
    if (thresholdC <= 0 || ch[k][0] < 0 || ch[k + 1][0] < 0)
        return ds;
    const int dc = (std::abs(ch[k + 1][0] - ch[k][0]) + std::abs(ch[k + 1][1] - ch[k][1]) +
                    std::abs(ch[k + 1][2] - ch[k][2])) *
                   1024 / thresholdC;
    return std::max(ds, dc);
}

/// L1 distance of a chromaticity from a reference (the walk's first two steps, summed: 2x); 0
/// when either is too dark to tell.
int chromaticityDeparture(const int ch[3], const int ref2[3]) noexcept
{
    if (ch[0] < 0 || ref2[0] < 0)
        return 0;
    return std::abs(2 * ch[0] - ref2[0]) + std::abs(2 * ch[1] - ref2[1]) +
           std::abs(2 * ch[2] - ref2[2]);
}

/// The sub-pixel position of the edge whose strongest step is from m to m + 1 (see walk()):
/// from the colours across it, pure card 2 steps before and pure background 3 steps after; -1
/// when the transition runs off the walk (its position would be biased).
float blendPosition(const int (*col)[3], int m, int n) noexcept
{
    const int first = m - 2, last = m + 3;  // pure card, pure background
    if (first < 0 || last >= n)
        return -1.f;
    const float d0 = static_cast<float>(col[first][0] - col[last][0]);
    const float d1 = static_cast<float>(col[first][1] - col[last][1]);
    const float d2 = static_cast<float>(col[first][2] - col[last][2]);
    const float den = d0 * d0 + d1 * d1 + d2 * d2;
    if (den < 16.f * 16.f * 24.f * 24.f)  // colours closer than ~24 levels: no usable blend
        return static_cast<float>(m) + 0.5f;
    float card = 0.f;
    for (int i = first + 1; i < last; ++i) {
        const float f = (static_cast<float>(col[i][0] - col[last][0]) * d0 +
                         static_cast<float>(col[i][1] - col[last][1]) * d1 +
                         static_cast<float>(col[i][2] - col[last][2]) * d2) /
                        den;
        card += std::clamp(f, 0.f, 1.f);
    }
    return static_cast<float>(first) + 0.5f + card;
}

/// Walks one sample line: from (x, y) in steps of (dx, dy) (one of them 0, the other +-1) for at
/// most `steps` pixels. Each step's saturation (and colour) is the mean over a short band of
/// 2 * band + 1 pixels that follows the edge's direction (offset `slope` pixels along the walk per
/// pixel across it), which cuts sensor noise without blurring the edge.
///
/// The edge is where the saturation gradient first exceeds `threshold` (§2 step 5) or, beyond the
/// dissertation, where the chromaticity has left that of the walk's start (the card, locally: the
/// shading of the card does not change it) by more than `chromaThreshold` (L1, 16 * 255 units): a
/// card in front of a background as saturated as itself (leaves, a coloured shirt) has no
/// saturation edge, but its chromaticity still changes there. A departure from the start rather
/// than a step between neighbours: sensor noise on a dark card makes single steps, not a lasting
/// departure. Its sub-pixel position
/// comes from the colours around it, not from S: across a box-filtered (anti-aliased or slightly
/// blurred) edge each pixel is a blend of the card colour (2 steps before the gradient peak) and
/// the background colour (3 steps after it), so the card's share summed over the transition is
/// the edge's distance from the last pure card pixel. S itself is not monotonic across an edge
/// between complementary colours (the blend is grey), so its gradient would only place the edge
/// at half-pixel steps. With `brightThreshold`, a walk on which neither cue marks an edge anywhere
/// takes the first lasting departure of brightness instead (`byBrightness`): a card over a
/// background of its own colour. Returns the offset (in steps from the start), or -1.
float walk(const ConstImageView& rgb, int bpp, int x, int y, int dx, int dy, int steps, int band,
           float slope, int threshold, int chromaThreshold, int brightThreshold,
           bool& byBrightness) noexcept
{
    byBrightness = false;
    // Saturation and colour in 1/16 units so the band mean keeps some fraction.
    int s[kMaxWalk];
    int col[kMaxWalk][3];
    int ch[kMaxWalk][3];
    int offsets[2 * kMaxBand + 1];
    const int b = std::clamp(band, 0, kMaxBand);
    // A horizontal walk's band uses every other row: with interlaced video (odd rows from the
    // previous field) it then sees one field only, the even (current) one. A vertical walk
    // crosses odd rows and deinterlaces them (fieldPixel).
    const int stride = dx != 0 ? 2 : 1;
    for (int j = -b; j <= b; ++j)
        offsets[j + b] = static_cast<int>(std::lround(static_cast<float>(j * stride) * slope));
    int n = 0;
    for (; n < steps && n < kMaxWalk; ++n, x += dx, y += dy) {
        if (x < 0 || y < 0 || x >= rgb.width || y >= rgb.height)
            break;
        int sum = 0, count = 0, c0 = 0, c1 = 0, c2 = 0;
        for (int j = -b; j <= b; ++j) {
            // Across the walk: rows for a horizontal walk, columns for a vertical one.
            const int px = dx != 0 ? x + offsets[j + b] : x + j;
            const int py = dx != 0 ? y + j * stride : y + offsets[j + b];
            if (px < 0 || py < 0 || px >= rgb.width || py >= rgb.height)
                continue;
            std::uint8_t p[3];
            fieldPixel(rgb, bpp, px, py, p);
            sum += saturation8(p);
            c0 += p[0];
            c1 += p[1];
            c2 += p[2];
            ++count;
        }
        const int half = count / 2;
        const int d = count > 0 ? count : 1;
        s[n] = (sum * 16 + half) / d;
        col[n][0] = (c0 * 16 + half) / d;
        col[n][1] = (c1 * 16 + half) / d;
        col[n][2] = (c2 * 16 + half) / d;
        if (chromaThreshold > 0)
            chromaticityOf(col[n], ch[n]);
    }
    threshold *= 16;
    int ref2[3] = {0, 0, 0};  // the start's chromaticity, twice (two steps summed)
    if (chromaThreshold > 0 && n >= 2) {
        for (int c = 0; c < 3; ++c)
            ref2[c] = ch[0][c] + ch[1][c];
        if (ch[0][0] < 0 || ch[1][0] < 0)
            ref2[0] = -1;
    }
    // g_k, the step from k to k + 1, sits half-way between the two pixels.
    for (int k = 0; k + 1 < n; ++k) {
        const bool saturationEdge = std::abs(s[k + 1] - s[k]) >= threshold;
        const bool chromaEdge = chromaThreshold > 0 && k >= 1 &&
                                chromaticityDeparture(ch[k + 1], ref2) >= 2 * chromaThreshold;
        if (!saturationEdge && !chromaEdge)
            continue;
        int m = k;
        while (m + 2 < n && stepStrength(s, ch, m + 1, threshold, chromaThreshold) >
                                stepStrength(s, ch, m, threshold, chromaThreshold))
            ++m;
        return blendPosition(col, m, n);
    }
    if (brightThreshold <= 0 || n < 2)
        return -1.f;
    // No colour cue anywhere on the walk: the first lasting departure of brightness from the
    // start's (as for chromaticity: a departure, not a neighbour step, so noise does not count),
    // placed at the strongest brightness step from there.
    int lum[kMaxWalk];
    for (int k = 0; k < n; ++k)
        lum[k] = col[k][0] + col[k][1] + col[k][2];
    const int lumRef2 = lum[0] + lum[1];
    const int need = 2 * 3 * 16 * brightThreshold;  // 2x (two steps), 3 channels, 1/16 units
    for (int k = 1; k + 1 < n; ++k) {
        if (std::abs(2 * lum[k + 1] - lumRef2) < need)
            continue;
        int m = k;
        while (m + 2 < n && std::abs(lum[m + 2] - lum[m + 1]) > std::abs(lum[m + 1] - lum[m]))
            ++m;
        byBrightness = true;
        return blendPosition(col, m, n);
    }
    return -1.f;
}

/// How far the quad reaches inward from edge `e` (outward normal nx, ny): its farthest corner.
float depthAcross(const Quad& q, int e, float nx, float ny) noexcept
{
    float deepest = 0.f;
    for (const Point2f& p : q)
        deepest = std::max(deepest, nx * (q[e].x - p.x) + ny * (q[e].y - p.y));
    return deepest;
}

/// Liang-Barsky: narrows [t0, t1] to the part of a + t (ex, ey) inside [0, maxX] x [0, maxY].
void clipToFrame(Point2f a, float ex, float ey, float maxX, float maxY, float& t0,
                 float& t1) noexcept
{
    const float p[4] = {-ex, ex, -ey, ey};
    const float q[4] = {a.x, maxX - a.x, a.y, maxY - a.y};
    for (int i = 0; i < 4; ++i) {
        if (std::fabs(p[i]) < 1e-9f) {
            if (q[i] < 0.f)
                t1 = t0 - 1.f;  // parallel and outside: empty
            continue;
        }
        const float r = q[i] / p[i];
        if (p[i] < 0.f)
            t0 = std::max(t0, r);
        else
            t1 = std::min(t1, r);
    }
}

/// The standard error of a least-squares line's angle over its `n` inliers: the residuals' standard
/// deviation (at least a tenth of a pixel: the walks' positions are whole pixels) over the root of
/// their squared spread along the line about its mean.
float angleError(const Point2f* pts, int count, const std::uint8_t* isInlier, const Line2f& line,
                 int n) noexcept
{
    float mean = 0.f;
    for (int k = 0; k < count; ++k)
        if (isInlier[k])
            mean += line.ny * pts[k].x - line.nx * pts[k].y;
    mean /= static_cast<float>(n);
    float residual = 0.f, spread = 0.f;
    for (int k = 0; k < count; ++k)
        if (isInlier[k]) {
            const float d = line.distance(pts[k]),
                        at = line.ny * pts[k].x - line.nx * pts[k].y - mean;
            residual += d * d;
            spread += at * at;
        }
    const float sigma =
        std::max(std::sqrt(residual / static_cast<float>(std::max(n - 2, 1))), 0.1f);
    return sigma / std::sqrt(std::max(spread, 1.f));
}

/// The edge's line from its points (outward normal of the input edge (nx, ny)): RANSAC, then
/// the checks that it is the edge's: enough inliers, spread along the edge over `minSpan` pixels
/// (points bunched on a short piece do not fix its direction), and, when guided, not turned away
/// from the expected edge. Returns the inlier count, 0 when not fitted. `turnSigma`: the line's
/// angle standard error (radians), the inliers' residual over their spread along the line.
int fitEdge(const Point2f* pts, int count, float nx, float ny, float minSpan, int normals,
            const EdgeRefinementOptions& o, Line2f& line, float& turnSigma) noexcept
{
    if (count < 3)
        return 0;
    std::uint8_t isInlier[kMaxNormalsPerEdge];
    const int in = fitLineRansac(pts, count, o.inlierDistance, o.ransacIterations, line, isInlier);
    const int needed = std::max(3, static_cast<int>(std::ceil(o.minInlierShare * normals)));
    if (in < needed)
        return 0;
    float lo = 1e30f, hi = -1e30f;
    for (int k = 0; k < count; ++k)
        if (isInlier[k]) {
            const float at = ny * pts[k].x - nx * pts[k].y;  // along the edge
            lo = std::min(lo, at);
            hi = std::max(hi, at);
        }
    if (hi - lo < minSpan)
        return 0;
    turnSigma = angleError(pts, count, isInlier, line, in);
    // Guided by an expected edge: a line turned away from it is something else's outline.
    if (o.maxSeedDistance > 0.f && std::fabs(line.nx * ny - line.ny * nx) > o.maxSeedTurn)
        return 0;
    // Keep the outward orientation of the input edge.
    if (line.nx * nx + line.ny * ny < 0.f)
        line = {-line.nx, -line.ny, -line.c};
    return in;
}

}  // namespace

bool refineQuad(const ConstImageView& rgb, const Quad& quad, const EdgeRefinementOptions& options,
                EdgeRefinement& out) noexcept
{
    out = EdgeRefinement{};
    out.quad = quad;
    const int bpp = rgb.format == PixelFormat::XRGB8888                                      ? 4
                    : (rgb.format == PixelFormat::RGB24 || rgb.format == PixelFormat::BGR24) ? 3
                                                                                             : 0;
    if (bpp == 0 || rgb.empty())
        return false;
    float shortest = 1e30f;
    for (int i = 0; i < 4; ++i) {
        const Point2f a = quad[i], b = quad[(i + 1) % 4];
        shortest = std::min(shortest, std::hypot(b.x - a.x, b.y - a.y));
    }
    if (!(shortest >= 3.f))
        return false;
    const int threshold =
        std::max(1, static_cast<int>(std::lround(options.saturationGradient * 255.f)));
    const int chromaThreshold =
        options.chromaticityStep > 0.f
            ? std::max(1, static_cast<int>(std::lround(options.chromaticityStep * 4080.f)))
            : 0;
    const int brightThreshold =
        options.brightnessStep > 0.f
            ? std::max(1, static_cast<int>(std::lround(options.brightnessStep * 255.f)))
            : 0;
    const int normals = std::clamp(options.normalsPerEdge, 2, kMaxNormalsPerEdge);
    // Never start past the middle of the card: the far edge would be found instead.
    const float outside = options.searchOutside;

    for (int e = 0; e < 4; ++e) {
        const Point2f a = quad[e], b = quad[(e + 1) % 4];
        const float ex = b.x - a.x, ey = b.y - a.y;
        const float len = std::hypot(ex, ey);
        // Outward normal of a clockwise-on-screen polygon: (ey, -ex) / len.
        const float nx = ey / len, ny = -ex / len;
        const float inside = std::min(options.searchInside,
                                      options.deepFraction > 0.f
                                          ? options.deepFraction * depthAcross(quad, e, nx, ny)
                                          : 0.35f * shortest);
        const bool acrossRows = std::fabs(nx) >= std::fabs(ny);  // near-vertical edge
        const float along = acrossRows ? std::fabs(nx) : std::fabs(ny);
        const int dir = (acrossRows ? nx : ny) > 0.f ? 1 : -1;
        // Along-walk shift of the edge per pixel across the walk (|slope| <= 1).
        const float slope = acrossRows ? ex / (std::fabs(ey) > 1e-6f ? ey : 1e-6f)
                                       : ey / (std::fabs(ex) > 1e-6f ? ex : 1e-6f);
        const int steps =
            std::min(kMaxWalk, static_cast<int>(std::ceil((inside + outside) / along)) + 1);
        // Spread the sample lines over the part of the edge inside the frame, so an edge with a
        // corner outside still gets all of them (its corner is then extrapolated).
        float t0 = options.endMargin, t1 = 1.f - options.endMargin;
        clipToFrame(a, ex, ey, static_cast<float>(rgb.width - 1),
                    static_cast<float>(rgb.height - 1), t0, t1);
        // Too little of the edge in view to tell its direction: it keeps its input line.
        const float minSpan = std::max(8.f, options.minEdgeSpan * len);
        if ((t1 - t0) * len < minSpan) {
            lineThrough(a, b, out.lines[e]);
            continue;
        }
        Point2f pts[kMaxNormalsPerEdge];
        int count = 0;
        for (int k = 0; k < normals; ++k) {
            const float t =
                t0 + (t1 - t0) * (static_cast<float>(k) + 0.5f) / static_cast<float>(normals);
            const float px = a.x + t * ex, py = a.y + t * ey;
            int x, y;
            float start;  // coordinate of the walk's first pixel along its direction
            if (acrossRows) {
                y = static_cast<int>(std::lround(py)) & ~1;  // even rows: see walk()
                start = px - static_cast<float>(dir) * inside / along;
                x = static_cast<int>(std::lround(start));
                start = static_cast<float>(x);
            } else {
                x = static_cast<int>(std::lround(px));
                start = py - static_cast<float>(dir) * inside / along;
                y = static_cast<int>(std::lround(start));
                start = static_cast<float>(y);
            }
            if (x < 0 || y < 0 || x >= rgb.width || y >= rgb.height)
                continue;
            ++out.normals;
            bool byBrightness = false;
            const float offset =
                walk(rgb, bpp, x, y, acrossRows ? dir : 0, acrossRows ? 0 : dir, steps,
                     options.band, slope, threshold, chromaThreshold, brightThreshold, byBrightness);
            if (offset < 0.f)
                continue;
            const float pos = start + static_cast<float>(dir) * offset;
            const Point2f p = acrossRows ? Point2f{pos, static_cast<float>(y)}
                                         : Point2f{static_cast<float>(x), pos};
            // Guided by an expected edge: points far from it belong to something else.
            if (options.maxSeedDistance > 0.f &&
                std::fabs(nx * (p.x - a.x) + ny * (p.y - a.y)) > options.maxSeedDistance)
                continue;
            pts[count++] = p;
            out.brightnessSamples += byBrightness;
        }
        out.samples += count;
        Line2f line;
        float turnSigma = 0.f;
        const int in = fitEdge(pts, count, nx, ny, minSpan, normals, options, line, turnSigma);
        if (in > 0) {
            out.lines[e] = line;
            out.turnSigma[e] = turnSigma;
            out.fitted[e] = true;
            out.inliers += in;
            ++out.edgesFitted;
        } else {
            lineThrough(a, b, out.lines[e]);
        }
    }
    for (int i = 0; i < 4; ++i) {
        Point2f p;
        if (intersectLines(out.lines[(i + 3) % 4], out.lines[i], p) && std::isfinite(p.x) &&
            std::isfinite(p.y))
            out.quad[i] = p;
    }
    return true;
}

}  // namespace vision
