#include "liveness_eval.hpp"

#include "face_sequence.hpp"
#include "vision/corner_detector.hpp"
#include "vision/image_pyramid.hpp"
#include "vision/liveness_cue.hpp"
#include "vision/motion_model.hpp"
#include "vision/motion_stage.hpp"
#include "vision/optical_flow.hpp"
#include "vision/pipeline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <vector>

namespace mirror_eval {

namespace {

using vision::Point2f;

constexpr std::array<int, 12> kSteps = {1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25};
constexpr const char* kKinds[] = {"living", "moving", "static", "passed"};
constexpr int kKindCount = 4;
constexpr const char* kCues[] = {"sway",     "sway_z", "halves", "rigid", "together",
                                 "nonrigid", "change", "noise",  "alive"};
constexpr int kCueCount = 9;
constexpr int kMaxCorners = 40;  ///< FaceTrackerOptions::maxCornersPerFace

/// One face followed from the frame its window starts.
struct Window {
    int start = 0;
    int id = 0;
    int kind = 0;  ///< index into kKinds (a static face becomes `passed` once a moving one nears)
    BoxF box{};    ///< the truth box at the start, frame pixels
    Point2f centre{};
    float size = 0.f;  ///< working pixels
    std::vector<Point2f> origin, pos;
    Point2f medianSum{};
    double noise = 0.0;  ///< sum over the steps of the corner variance (per axis) / corners
    /// Sums over the steps of the median flows of the corners left, right, above and below the
    /// centre.
    std::array<Point2f, 4> halfSums{};
    vision::SwayHistory history;  ///< LivenessCue's record of the steps
    bool alive = false;           ///< LivenessCue said it swayed, at this step or before
    int steps = 0;
    cv::Mat startGray;  ///< the inner box at the start
    vision::Rect inner{};
};

float median(std::vector<float>& v)
{
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

vision::Rect innerBox(Point2f c, float size, vision::Size image)
{
    const float s = 0.7f * size;
    return vision::clipped({static_cast<int>(c.x - s * 0.5f), static_cast<int>(c.y - s * 0.5f),
                            static_cast<int>(s), static_cast<int>(s)},
                           image.width, image.height);
}

cv::Mat cropOf(const vision::ConstImageView& gray, vision::Rect r)
{
    const cv::Mat all(gray.height, gray.width, CV_8U, const_cast<std::uint8_t*>(gray.data),
                      static_cast<std::size_t>(gray.stride));
    return all(cv::Rect(r.x, r.y, r.width, r.height)).clone();
}

/// The blocks' local change since the start, the box's brightness change removed.
double localChange(const cv::Mat& before, const cv::Mat& now)
{
    const double gain = cv::mean(before)[0] / std::max(1.0, cv::mean(now)[0]);
    std::vector<float> blocks;
    for (int y = 0; y + 8 <= before.rows; y += 8) {
        for (int x = 0; x + 8 <= before.cols; x += 8) {
            double sum = 0;
            for (int v = y; v < y + 8; ++v)
                for (int u = x; u < x + 8; ++u)
                    sum += std::fabs(before.at<std::uint8_t>(v, u) -
                                     gain * now.at<std::uint8_t>(v, u));
            blocks.push_back(static_cast<float>(sum / 64.0));
        }
    }
    if (blocks.size() < 4)
        return 0.0;
    std::vector<float> sorted = blocks;
    std::sort(sorted.begin(), sorted.end());
    return sorted[sorted.size() * 9 / 10] - sorted[sorted.size() / 2];
}

class LivenessRun {
public:
    LivenessRun(const LivenessEvalOptions& o, vision::Size frameSize)
        : o_(o),
          motion_(frameSize, vision::MotionStageOptions{o.downscale, {}}),
          work_{frameSize.width / o.downscale, frameSize.height / o.downscale},
          corners_(work_, vision::CornerDetectorOptions{kMaxCorners, 0.01f, 5.f, 3}),
          pyramids_{vision::ImagePyramid(work_, 4), vision::ImagePyramid(work_, 4)},
          grays_{vision::ImageBuffer(work_.width, work_.height, vision::PixelFormat::Gray8),
                 vision::ImageBuffer(work_.width, work_.height, vision::PixelFormat::Gray8)}
    {
    }

    void frame(const cv::Mat& bgr, int index, const std::vector<TruthFace>& truth);
    /// values_[kind][cue][step index]
    std::vector<double> values_[kKindCount][kCueCount][kSteps.size()];

private:
    void startWindows(int index, const std::vector<TruthFace>& truth);
    void step(Window& w);
    static void markPassed(Window& w, const std::vector<TruthFace>& truth);
    void record(Window& w, std::size_t k);

    LivenessEvalOptions o_;
    vision::MotionStage motion_;
    vision::Size work_;
    vision::CornerDetector corners_;
    vision::PyramidalLucasKanade flow_{};
    vision::LivenessCue cue_;
    vision::ImagePyramid pyramids_[2];
    vision::ImageBuffer grays_[2];
    int current_ = 0;
    std::vector<Window> windows_;
};

void LivenessRun::frame(const cv::Mat& bgr, int index, const std::vector<TruthFace>& truth)
{
    vision::FrameState state;
    vision::Frame f;
    f.image = {bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step),
               vision::PixelFormat::BGR24};
    f.sequence = static_cast<std::uint64_t>(index);
    vision::Pipeline::begin(state, f);
    motion_.process(state);
    current_ = 1 - current_;
    const vision::ConstImageView g = motion_.gray();
    for (int y = 0; y < work_.height; ++y)
        std::memcpy(grays_[current_].view().row(y), g.row(y), static_cast<std::size_t>(g.width));
    pyramids_[current_].build(grays_[current_].view());
    for (Window& w : windows_) {
        step(w);
        markPassed(w, truth);
    }
    std::erase_if(windows_,
                  [](const Window& w) { return w.steps >= kSteps.back() || w.pos.size() < 3; });
    if (index % o_.every == 0)
        startWindows(index, truth);
}

void LivenessRun::startWindows(int index, const std::vector<TruthFace>& truth)
{
    const float k = 1.f / static_cast<float>(o_.downscale);
    for (const TruthFace& t : truth) {
        if (!wholeInFrame(t.box, {work_.width * o_.downscale, work_.height * o_.downscale}))
            continue;
        Window w;
        w.start = index;
        w.id = t.id;
        w.kind = t.moving ? (t.id == 0 ? 0 : 1) : 2;
        w.box = t.box;
        markPassed(w, truth);
        w.centre = {t.centre.x * k, t.centre.y * k};
        w.size = std::max(t.box.width, t.box.height) * k;
        w.inner = innerBox(w.centre, w.size, work_);
        corners_.setMinDistance(std::max(2.f, 0.05f * w.size));
        std::array<vision::Corner, kMaxCorners> found{};
        const int n = corners_.detect(grays_[current_].view(), w.inner, found.data(), kMaxCorners);
        for (int i = 0; i < n; ++i)
            w.pos.push_back(found[static_cast<std::size_t>(i)].position);
        w.origin = w.pos;
        w.startGray = cropOf(grays_[current_].view(), w.inner);
        if (w.pos.size() >= 6)
            windows_.push_back(std::move(w));
    }
}

void LivenessRun::markPassed(Window& w, const std::vector<TruthFace>& truth)
{
    // A static face a moving one comes near (their boxes, the static one grown by half, meet):
    // its corners can be dragged by the passer-by.
    if (w.kind != 2)
        return;
    const BoxF grown{w.box.x - 0.25f * w.box.width, w.box.y - 0.25f * w.box.height,
                     1.5f * w.box.width, 1.5f * w.box.height};
    for (const TruthFace& t : truth)
        if (t.moving && iou(grown, t.box) > 0.f)
            w.kind = 3;
}

/// Each half of the face's corners (left, right, above, below its centre) adds its median flow.
void addHalves(Window& w, const std::vector<Point2f>& from, const std::vector<Point2f>& to,
               const std::vector<std::uint8_t>& in)
{
    for (int h = 0; h < 4; ++h) {
        std::vector<float> dx, dy;
        for (std::size_t i = 0; i < from.size(); ++i) {
            const float side = h < 2 ? from[i].x - w.centre.x : from[i].y - w.centre.y;
            if (in[i] && (h % 2 == 0 ? side < 0.f : side >= 0.f)) {
                dx.push_back(to[i].x - from[i].x);
                dy.push_back(to[i].y - from[i].y);
            }
        }
        if (dx.size() >= 2) {
            w.halfSums[static_cast<std::size_t>(h)].x += median(dx);
            w.halfSums[static_cast<std::size_t>(h)].y += median(dy);
        }
    }
}

/// The least, over the four halves, of the fraction of the common motion `m` a half followed.
double halvesAlong(const Window& w, Point2f m)
{
    const double m2 = static_cast<double>(m.x) * m.x + static_cast<double>(m.y) * m.y;
    double least = 1.0;
    for (const Point2f& h : w.halfSums)
        least = std::min(least, (h.x * m.x + h.y * m.y) / std::max(1e-12, m2));
    return least;
}

void LivenessRun::step(Window& w)
{
    const std::size_t n = w.pos.size();
    std::vector<Point2f> to(n);
    std::vector<vision::FlowStatus> status(n);
    flow_.track(pyramids_[1 - current_], pyramids_[current_], w.pos.data(), to.data(),
                status.data(), static_cast<int>(n));
    std::vector<Point2f> from, dest, origin;
    for (std::size_t i = 0; i < n; ++i) {
        if (status[i] != vision::FlowStatus::Tracked)
            continue;
        from.push_back(w.pos[i]);
        dest.push_back(to[i]);
        origin.push_back(w.origin[i]);
    }
    vision::MotionModel model;
    std::vector<std::uint8_t> in(from.size());
    const int inliers =
        from.size() >= 3
            ? vision::fitMotionRobust(from.data(), dest.data(), static_cast<int>(from.size()),
                                      w.centre, vision::MotionFitOptions{}, model, in.data())
            : 0;
    w.pos.clear();
    w.origin.clear();
    std::vector<float> dx, dy;
    double var = 0;
    for (std::size_t i = 0; i < from.size() && inliers >= 3; ++i) {
        if (!in[i])
            continue;
        w.pos.push_back(dest[i]);
        w.origin.push_back(origin[i]);
        dx.push_back(dest[i].x - from[i].x);
        dy.push_back(dest[i].y - from[i].y);
        const Point2f p = model.apply(from[i]);
        var += 0.5 * (std::pow(dest[i].x - p.x, 2) + std::pow(dest[i].y - p.y, 2));
    }
    if (w.pos.size() < 3) {
        w.pos.clear();
        return;
    }
    const double m = static_cast<double>(w.pos.size());
    const float mx = median(dx), my = median(dy);
    w.medianSum.x += mx;
    w.medianSum.y += my;
    w.noise += var / m / m;
    addHalves(w, from, dest, in);
    cue_.addFlowStep(w.history, from, dest, in, model);
    w.alive = w.alive || vision::LivenessCue::swayed(w.history);
    w.centre = model.apply(w.centre);
    ++w.steps;
    for (std::size_t k = 0; k < kSteps.size(); ++k)
        if (w.steps == kSteps[k])
            record(w, k);
}

void LivenessRun::record(Window& w, std::size_t k)
{
    const int n = static_cast<int>(w.pos.size());
    vision::MotionModel rigid;
    vision::fitMotionLeastSquares(w.origin.data(), w.pos.data(), n, nullptr, w.centre,
                                  vision::MotionKind::Similarity, rigid);
    const double t = std::hypot(rigid.b1, rigid.b2);
    int together = 0;
    double residual = 0;
    for (int i = 0; i < n; ++i) {
        const Point2f a = w.origin[static_cast<std::size_t>(i)];
        const Point2f b = w.pos[static_cast<std::size_t>(i)];
        const Point2f p = rigid.apply(a);
        residual += std::pow(b.x - p.x, 2) + std::pow(b.y - p.y, 2);
        together += t > 0 && ((b.x - a.x) * rigid.b1 + (b.y - a.y) * rigid.b2) >= 0.5 * t * t;
    }
    const double sway = std::hypot(w.medianSum.x, w.medianSum.y);
    const double values[kCueCount] = {
        sway,
        sway / std::sqrt(std::max(1e-8, w.noise)),
        halvesAlong(w, w.medianSum),
        t,
        static_cast<double>(together) / n,
        std::sqrt(residual / n),
        localChange(w.startGray, cropOf(grays_[current_].view(), w.inner)),
        std::sqrt(w.noise / w.steps),
        w.alive ? 1.0 : 0.0,
    };
    for (int c = 0; c < kCueCount; ++c)
        values_[w.kind][c][k].push_back(values[c]);
    if (o_.perWindow)
        std::printf(
            "window start=%d id=%d kind=%s steps=%d corners=%d sway=%.3f sway_z=%.2f "
            "halves=%.2f rigid=%.3f together=%.2f nonrigid=%.3f change=%.2f noise=%.4f alive=%d\n",
            w.start, w.id, kKinds[w.kind], w.steps, n, values[0], values[1], values[2], values[3],
            values[4], values[5], values[6], values[7], w.alive ? 1 : 0);
}

double percentileOf(const std::vector<double>& sorted, double q)
{
    const auto i = static_cast<std::size_t>(q * static_cast<double>(sorted.size()));
    return sorted[std::min(sorted.size() - 1, i)];
}

constexpr int kAlive = kCueCount - 1;  ///< the cue LivenessCue decides: 1 once it swayed

double meanOf(const std::vector<double>& v)
{
    double sum = 0.0;
    for (const double x : v)
        sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

void printTable(const LivenessRun& run, std::FILE* out)
{
    std::fprintf(out, "%-7s %-9s %5s %6s %8s %8s %8s %8s %8s %8s %8s\n", "kind", "cue", "steps",
                 "n", "min", "p1", "p5", "p50", "p95", "p99", "max");
    for (int kind = 0; kind < kKindCount; ++kind) {
        for (int c = 0; c < kAlive; ++c) {
            for (std::size_t k = 0; k < kSteps.size(); ++k) {
                std::vector<double> v = run.values_[kind][c][k];
                if (v.empty())
                    continue;
                std::sort(v.begin(), v.end());
                std::fprintf(out, "%-7s %-9s %5d %6zu", kKinds[kind], kCues[c], kSteps[k],
                             v.size());
                for (const double q : {0.0, 0.01, 0.05, 0.5, 0.95, 0.99, 1.0})
                    std::fprintf(out, " %8.3f", percentileOf(v, q));
                std::fputc('\n', out);
            }
        }
    }
}

/// LivenessCue's verdict: the fraction of each kind's windows that swayed within k steps.
void printSwayed(const LivenessRun& run, std::FILE* out)
{
    std::fprintf(out, "LivenessCue::swayed, fraction of the windows within k steps:\n%-7s", "kind");
    for (const int k : kSteps)
        std::fprintf(out, " %6d", k);
    std::fputc('\n', out);
    for (int kind = 0; kind < kKindCount; ++kind) {
        if (run.values_[kind][kAlive][0].empty())
            continue;
        std::fprintf(out, "%-7s", kKinds[kind]);
        for (std::size_t k = 0; k < kSteps.size(); ++k)
            std::fprintf(out, " %6.3f", meanOf(run.values_[kind][kAlive][k]));
        std::fputc('\n', out);
    }
    const std::size_t half = 8;  // kSteps[8] == 12: half a second at 25 fps
    std::fprintf(out,
                 "liveness: living_swayed_12=%.4f moving_swayed_12=%.4f static_swayed=%.4f "
                 "passed_swayed=%.4f\n",
                 meanOf(run.values_[0][kAlive][half]), meanOf(run.values_[1][kAlive][half]),
                 meanOf(run.values_[2][kAlive][kSteps.size() - 1]),
                 meanOf(run.values_[3][kAlive][kSteps.size() - 1]));
}

}  // namespace

int runLivenessEval(const LivenessEvalOptions& o, std::FILE* out, std::FILE* err)
{
    try {
        if (o.downscale < 1 || o.downscale > 4)
            throw std::runtime_error("--downscale must be in 1..4");
        if (o.every < 1)
            throw std::runtime_error("--every must be >= 1");
        const FaceSequence seq = loadFaceSequence(o.frames, o.truth, 0, o.maxFrames);
        std::unique_ptr<LivenessRun> run;
        for (std::size_t k = 0; k < seq.frames.size(); ++k) {
            const cv::Mat bgr = cv::imread(seq.frames[k], cv::IMREAD_COLOR);
            if (bgr.empty())
                throw std::runtime_error("frame " + seq.frames[k] + ": cannot decode");
            if (!run)
                run = std::make_unique<LivenessRun>(o, vision::Size{bgr.cols, bgr.rows});
            run->frame(bgr, static_cast<int>(k), seq.truth[k]);
        }
        std::fprintf(out,
                     "liveness eval: %zu frames of %s (%s), a window on every face wholly in "
                     "view every %d frames, working image frame / %d\n",
                     seq.frames.size(), o.frames.c_str(),
                     seq.composed ? "composed: moving and static faces" : "FGNet: living", o.every,
                     o.downscale);
        printTable(*run, out);
        printSwayed(*run, out);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(err, "mirror-eval liveness: %s\n", e.what());
        return 1;
    }
}

}  // namespace mirror_eval
