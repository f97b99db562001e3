#include "card_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace mirror_eval {

namespace {

bool insideImage(vision::Point2f p, vision::Size size) noexcept
{
    return p.x >= -0.5f && p.y >= -0.5f && p.x <= size.width - 0.5f && p.y <= size.height - 0.5f;
}

int cornersInside(const TruthRow& row, vision::Size size) noexcept
{
    int n = 0;
    for (const auto& p : row.quad)
        n += insideImage(p, size);
    return n;
}

bool sameQuad(const vision::Quad& a, const vision::Quad& b, float tolerance) noexcept
{
    for (int k = 0; k < 4; ++k)
        if (std::abs(a[k].x - b[k].x) > tolerance || std::abs(a[k].y - b[k].y) > tolerance)
            return false;
    return true;
}

/// RMS distance of the corners from their mean position over frames [first, last).
double rmsDeviation(const std::vector<TrackedFrame>& tracked, int first, int last)
{
    double total = 0.0;
    const double n = last - first;
    for (int k = 0; k < 4; ++k) {
        double sx = 0, sy = 0;
        for (int i = first; i < last; ++i) {
            sx += tracked[i].quad[k].x;
            sy += tracked[i].quad[k].y;
        }
        const double mx = sx / n, my = sy / n;
        for (int i = first; i < last; ++i) {
            const double dx = tracked[i].quad[k].x - mx, dy = tracked[i].quad[k].y - my;
            total += dx * dx + dy * dy;
        }
    }
    return std::sqrt(total / (4.0 * n));
}

}  // namespace

void matchedCornerErrors(const vision::Quad& found, const vision::Quad& truth, float tiePx,
                         double errors[4]) noexcept
{
    auto sum = [](vision::Point2f p) { return static_cast<double>(p.x) + p.y; };
    double worst = std::numeric_limits<double>::infinity();
    for (int start = 0; start < 4; ++start) {
        // The truth's own labelling starts at its corner 0; another start only on a tie.
        if (start != 0 && sum(truth[start]) > sum(truth[0]) + tiePx)
            continue;
        double e[4], largest = 0.0;
        for (int k = 0; k < 4; ++k) {
            const vision::Point2f t = truth[(start + k) % 4];
            e[k] = std::hypot(static_cast<double>(found[k].x) - t.x,
                              static_cast<double>(found[k].y) - t.y);
            largest = std::max(largest, e[k]);
        }
        if (largest < worst) {
            worst = largest;
            std::copy(e, e + 4, errors);
        }
    }
}

CardMetrics computeCardMetrics(const std::vector<TruthRow>& truth,
                               const std::vector<TrackedFrame>& tracked, const CardEvalSettings& s)
{
    if (truth.size() != tracked.size())
        throw std::invalid_argument("card metrics: " + std::to_string(truth.size()) +
                                    " truth rows but " + std::to_string(tracked.size()) +
                                    " tracked frames");
    CardMetrics m;
    const int n = static_cast<int>(truth.size());
    m.frames = n;
    const int first = std::clamp(s.firstScored, 0, n);

    std::vector<double> errors;
    std::vector<char> fullyVisible(static_cast<std::size_t>(n), 0);
    bool inLostRun = false;
    for (int i = first; i < n; ++i) {
        const TruthRow& t = truth[i];
        const TrackedFrame& f = tracked[i];
        if (f.tracking)
            inLostRun = false;
        if (!t.hasCard) {
            ++m.absentFrames;
            m.falseTrackingFrames += f.tracking;
            continue;
        }
        const int inside = cornersInside(t, s.frameSize);
        fullyVisible[i] = inside == 4;
        if (inside < 3) {
            ++m.partialFrames;
            continue;
        }
        ++m.scoredFrames;
        if (!f.tracking) {
            ++m.lostFrames;
            m.lostStretches += !inLostRun;
            inLostRun = true;
            continue;
        }
        ++m.measuredFrames;
        bool within = true;
        double e[4];
        matchedCornerErrors(f.quad, t.quad, s.cornerTiePx, e);
        for (double ek : e) {
            errors.push_back(ek);
            within = within && ek <= s.withinPx;
        }
        m.withinFrames += within;
    }
    if (errors.empty()) {
        m.meanErrPx = m.p95ErrPx = m.maxErrPx = std::numeric_limits<double>::quiet_NaN();
    } else {
        double sum = 0.0;
        for (double e : errors)
            sum += e;
        m.meanErrPx = sum / static_cast<double>(errors.size());
        std::sort(errors.begin(), errors.end());
        // Nearest rank: the smallest error at or above 95 % of them.
        const std::size_t rank =
            static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(errors.size())));
        m.p95ErrPx = errors[std::max<std::size_t>(rank, 1) - 1];
        m.maxErrPx = errors.back();
    }
    m.withinFraction = m.scoredFrames > 0 ? static_cast<double>(m.withinFrames) / m.scoredFrames
                                          : std::numeric_limits<double>::quiet_NaN();

    // Recovery: stretches where there was no card or no track; each ends at the first frame with
    // both. Timed from the start of the card's last fully visible run before that frame (or the
    // stretch's start, if the card stayed fully visible and only the track was lost).
    long recoverSum = 0;
    for (int i = first; i < n;) {
        auto good = [&](int k) { return truth[k].hasCard && tracked[k].tracking; };
        if (good(i)) {
            ++i;
            continue;
        }
        const int start = i;
        while (i < n && !good(i))
            ++i;
        // [start, i) is the stretch; i the first good frame (or n).
        int visibleFrom = i < n ? i : n;
        while (visibleFrom > start && fullyVisible[visibleFrom - 1])
            --visibleFrom;
        if (i < n) {
            const int frames = fullyVisible[i] ? i - visibleFrom : 0;
            ++m.recoveries;
            recoverSum += frames;
            m.maxRecoverFrames = std::max(m.maxRecoverFrames, frames);
        } else if (visibleFrom < n) {
            // Never tracked again although the card was fully in view from visibleFrom on.
            ++m.unrecovered;
            m.maxRecoverFrames = std::max(m.maxRecoverFrames, n - visibleFrom);
        }
    }
    m.meanRecoverFrames = m.recoveries > 0 ? static_cast<double>(recoverSum) / m.recoveries : 0.0;

    // Jitter at rest: static truth, tracked throughout; the first frames settle.
    double jitterSum = 0.0;
    for (int i = first; i < n;) {
        if (!truth[i].hasCard || !tracked[i].tracking) {
            ++i;
            continue;
        }
        int j = i + 1;
        while (j < n && truth[j].hasCard && tracked[j].tracking &&
               sameQuad(truth[j].quad, truth[i].quad, s.restTolerancePx))
            ++j;
        const int from = i + s.restSettleFrames;
        if (j - from >= std::max(2, s.minRestFrames)) {
            const double jitter = rmsDeviation(tracked, from, j);
            ++m.restRuns;
            jitterSum += jitter;
            m.maxJitterPx = std::max(m.maxJitterPx, jitter);
        }
        i = j;
    }
    m.jitterPx = m.restRuns > 0 ? jitterSum / m.restRuns : std::numeric_limits<double>::quiet_NaN();
    return m;
}

std::string cardSummaryLine(const CardMetrics& m)
{
    char line[400];
    std::snprintf(line, sizeof line,
                  "card: mean_err_px=%.2f p95_err_px=%.2f within3px=%.3f lost_frames=%d "
                  "max_recover_frames=%d mean_recover_frames=%.2f unrecovered=%d jitter_px=%.3f "
                  "scored_frames=%d false_tracking_frames=%d lost_stretches=%d",
                  m.meanErrPx, m.p95ErrPx, m.withinFraction, m.lostFrames, m.maxRecoverFrames,
                  m.meanRecoverFrames, m.unrecovered, m.jitterPx, m.scoredFrames,
                  m.falseTrackingFrames, m.lostStretches);
    return line;
}

std::string cardReport(const CardMetrics& m)
{
    std::string out;
    char line[400];
    auto add = [&](int written) {
        (void)written;
        out += line;
        out += '\n';
    };
    add(std::snprintf(line, sizeof line,
                      "frames: %d (%d scored: card with at least 3 corners in view; %d with the "
                      "card mostly out of view; %d without card)",
                      m.frames, m.scoredFrames, m.partialFrames, m.absentFrames));
    add(std::snprintf(line, sizeof line,
                      "corner error: mean %.2f px, p95 %.2f px, max %.2f px (over %d tracked "
                      "scored frames)",
                      m.meanErrPx, m.p95ErrPx, m.maxErrPx, m.measuredFrames));
    add(std::snprintf(line, sizeof line, "all 4 corners within 3 px: %.3f (%d of %d scored frames)",
                      m.withinFraction, m.withinFrames, m.scoredFrames));
    add(std::snprintf(line, sizeof line,
                      "frames lost: %d (scored, not Tracking) in %d stretches; tracking with no "
                      "card in view: %d",
                      m.lostFrames, m.lostStretches, m.falseTrackingFrames));
    add(std::snprintf(line, sizeof line,
                      "frames to recover: max %d, mean %.2f over %d stretches without card or "
                      "track (the first acquisition included); never recovered: %d",
                      m.maxRecoverFrames, m.meanRecoverFrames, m.recoveries, m.unrecovered));
    if (m.restRuns > 0)
        add(std::snprintf(line, sizeof line,
                          "jitter at rest: %.3f px mean, %.3f px max (RMS corner deviation over %d "
                          "static stretches)",
                          m.jitterPx, m.maxJitterPx, m.restRuns));
    else
        add(std::snprintf(line, sizeof line, "jitter at rest: n/a (no static tracked stretch)"));
    return out;
}

}  // namespace mirror_eval
