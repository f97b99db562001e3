#pragma once
// Golden-section search for the minimum of a unimodal score on [lo, hi]: the sub-step refinement
// of the roll estimators (angles, and the mirror axis's offset). Each step keeps one of its two
// inner samples, so it costs one score evaluation.

#include <limits>

namespace vision {

/// The bracket a golden-section search ended with: its ends and its two inner samples (at a and
/// b, scores fa and fb).
struct GoldenSectionBracket {
    float lo, hi;
    float a, fa;
    float b, fb;
};

/// Narrows [lo, hi] until it is at most `tolerance` wide or `maxIterations` steps were taken.
/// `score(x)` is called with points inside the bracket only; it does not allocate here.
template <class Score>
GoldenSectionBracket goldenSection(float lo, float hi, float tolerance, Score&& score,
                                   int maxIterations = std::numeric_limits<int>::max()) noexcept
{
    constexpr float kInvPhi = 0.6180339887f;
    float a = hi - kInvPhi * (hi - lo);
    float b = lo + kInvPhi * (hi - lo);
    float fa = score(a);
    float fb = score(b);
    for (int iter = 0; iter < maxIterations && hi - lo > tolerance; ++iter) {
        if (fa <= fb) {
            hi = b;
            b = a;
            fb = fa;
            a = hi - kInvPhi * (hi - lo);
            fa = score(a);
        } else {
            lo = a;
            a = b;
            fa = fb;
            b = lo + kInvPhi * (hi - lo);
            fb = score(b);
        }
    }
    return {lo, hi, a, fa, b, fb};
}

}  // namespace vision
