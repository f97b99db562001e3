#include "card_run.hpp"

#include "scenarios.hpp"
#include "sequence_writer.hpp"
#include "test_paths.hpp"
#include "vision/card_tracker.hpp"
#include "vision/chromaticity.hpp"

#include <cmath>
#include <cstdio>

namespace card_test {

namespace {

vision::ConstImageView viewOf(const cv::Mat& bgr)
{
    return {bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step[0]),
            vision::PixelFormat::BGR24};
}

}  // namespace

TrackerRun runFrames(const cv::Mat& background, const FrameSource& scene,
                     const std::vector<int>& frames, std::uint64_t noiseSeed)
{
    const vision::Size size{background.cols, background.rows};
    vision::ChromaticityTable table;
    vision::ImageBuffer r(size.width, size.height, vision::PixelFormat::Gray8);
    vision::ImageBuffer g(size.width, size.height, vision::PixelFormat::Gray8);
    vision::ImageBuffer b(size.width, size.height, vision::PixelFormat::Gray8);
    const vision::ChromaticityPlanes planes{r.view(), g.view(), b.view()};
    vision::CardTracker tracker(size);
    TrackerRun run;
    run.frames = frames;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const cardgen::FrameSpec spec = scene(frames[k]);
        const cv::Mat bgr = cardgen::renderFrame(background, spec, noiseSeed * 100003u + frames[k]);
        const vision::ConstImageView image = viewOf(bgr);
        vision::convertChromaticity(table, image, planes);
        if (k == 0)
            tracker.train(image, planes, {0, 0, size.width, size.height});
        const vision::CardObservation& seen = tracker.process(image, planes);
        mirror_eval::TrackedFrame t;
        t.tracking = seen.state == vision::CardState::Tracking && seen.hasQuad;
        t.quad = seen.quad;
        t.problem = tracker.lastProblem();
        run.tracked.push_back(t);
        run.truth.push_back({static_cast<int>(k), spec.card, cardgen::truthCorners(spec.quad)});
    }
    mirror_eval::CardEvalSettings settings;
    settings.frameSize = size;
    run.metrics = mirror_eval::computeCardMetrics(run.truth, run.tracked, settings);
    return run;
}

TrackerRun runScenario(const std::string& scenario, std::uint32_t seed, int first, int last,
                       int length)
{
    const cv::Size size(720, 480);
    const cardgen::Scenario s(scenario, size, length, seed);
    const std::string path =
        cardgen::resolveBackground(scenario, s.backgrounds(), testing_support::sharedData(""), "");
    const cv::Mat background = cardgen::loadBackground(path, size);
    std::vector<int> frames = {0};
    for (int i = first; i <= last; ++i)
        frames.push_back(i);
    return runFrames(
        background, [&s](int i) { return s.frame(i); }, frames, seed);
}

std::string misses(const TrackerRun& run)
{
    std::string out;
    const vision::Size size{720, 480};
    for (std::size_t k = 1; k < run.truth.size(); ++k) {
        const mirror_eval::TruthRow& t = run.truth[k];
        if (!t.hasCard)
            continue;
        int inside = 0;
        for (const auto& p : t.quad)
            inside += p.x >= -0.5f && p.y >= -0.5f && p.x <= size.width - 0.5f &&
                      p.y <= size.height - 0.5f;
        if (inside < 3)
            continue;
        const mirror_eval::TrackedFrame& f = run.tracked[k];
        char text[96];
        if (!f.tracking) {
            std::snprintf(text, sizeof text, " %d:lost(%s)", run.frames[k], f.problem);
            out += text;
            continue;
        }
        double worst = 0.0;
        for (int c = 0; c < 4; ++c)
            worst = std::max(worst, std::hypot(static_cast<double>(f.quad[c].x - t.quad[c].x),
                                               static_cast<double>(f.quad[c].y - t.quad[c].y)));
        if (worst > 3.0) {
            std::snprintf(text, sizeof text, " %d:%.1fpx", run.frames[k], worst);
            out += text;
        }
    }
    return out;
}

}  // namespace card_test
