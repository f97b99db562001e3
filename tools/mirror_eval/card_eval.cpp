#include "card_eval.hpp"

#include "platform/file_source.hpp"
#include "vision/card_stage.hpp"
#include "vision/chromaticity_stage.hpp"
#include "vision/deinterlace_stage.hpp"
#include "vision/frame_check_stage.hpp"
#include "vision/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <memory>
#include <stdexcept>

namespace mirror_eval {

std::vector<TrackedFrame> runCardTracker(const CardEvalOptions& o, std::size_t truthRows,
                                         vision::Size& frameSize)
{
    platform::FileSource source(o.video, /*loop=*/false, platform::ReplayRate::max(), 30.0);
    if (!source.isVideo() && source.imageCount() != truthRows)
        throw std::runtime_error("frame count mismatch: " + o.video + " has " +
                                 std::to_string(source.imageCount()) + " frames, " + o.truth +
                                 " has " + std::to_string(truthRows) + " rows");
    frameSize = source.size();

    // Exactly the firmware's vision pipeline for the card.
    vision::Pipeline pipeline;
    pipeline.add(std::make_unique<vision::FrameCheckStage>(frameSize, source.format()));
    if (o.deinterlace)
        pipeline.add(std::make_unique<vision::DeinterlaceStage>(frameSize, source.format()));
    pipeline.add(std::make_unique<vision::ChromaticityStage>(frameSize));
    auto cardStage = std::make_unique<vision::CardStage>(frameSize);
    vision::CardStage& card = *cardStage;
    pipeline.add(std::move(cardStage));

    std::vector<TrackedFrame> tracked;
    tracked.reserve(truthRows);
    vision::FrameState state;
    for (;;) {
        vision::Frame frame;
        const platform::SourceStatus status = source.next(frame);
        if (status == platform::SourceStatus::EndOfStream)
            break;
        if (status != platform::SourceStatus::Ok)
            throw std::runtime_error(o.video + ": " + source.lastError());
        if (source.skippedFrames() > 0)
            throw std::runtime_error(o.video + ": " + source.lastError() +
                                     " (frames would no longer match the truth rows)");
        if (tracked.empty())
            card.requestTraining(o.trainFraction);
        vision::Pipeline::begin(state, frame);
        pipeline.run(state);
        if (tracked.empty() && !card.lastTrainingSucceeded())
            throw std::runtime_error(o.video + ": training on frame 0 failed" +
                                     (state.valid ? "" : std::string(" (") + state.problem + ")"));
        TrackedFrame t;
        if (state.card != nullptr && state.card->state == vision::CardState::Tracking &&
            state.card->hasQuad) {
            t.tracking = true;
            t.quad = state.card->quad;
        }
        t.problem = card.tracker().lastProblem();
        tracked.push_back(t);
    }
    if (tracked.size() != truthRows)
        throw std::runtime_error("frame count mismatch: " + o.video + " has " +
                                 std::to_string(tracked.size()) + " frames, " + o.truth + " has " +
                                 std::to_string(truthRows) + " rows");
    return tracked;
}

namespace {

void writePerFrame(const std::string& path, const std::vector<TruthRow>& truth,
                   const std::vector<TrackedFrame>& tracked, const CardEvalSettings& settings)
{
    std::ofstream out(path);
    if (!out)
        throw std::runtime_error("per-frame output " + path + ": cannot write");
    out << "frame,tracking,x0,y0,x1,y1,x2,y2,x3,y3,max_err_px,problem\n";
    char line[256];
    for (std::size_t i = 0; i < tracked.size(); ++i) {
        const TrackedFrame& f = tracked[i];
        if (!f.tracking) {
            std::snprintf(line, sizeof line, "%zu,0,,,,,,,,,,%s\n", i, f.problem);
        } else {
            double err = -1.0;
            if (truth[i].hasCard) {
                double e[4];
                matchedCornerErrors(f.quad, truth[i].quad, settings.cornerTiePx, e);
                err = *std::max_element(e, e + 4);
            }
            std::snprintf(line, sizeof line, "%zu,1,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%s,\n",
                          i, f.quad[0].x, f.quad[0].y, f.quad[1].x, f.quad[1].y, f.quad[2].x,
                          f.quad[2].y, f.quad[3].x, f.quad[3].y,
                          err < 0 ? "" : std::to_string(err).c_str());
        }
        out << line;
    }
}

}  // namespace

int runCardEval(const CardEvalOptions& o, std::FILE* out, std::FILE* err)
{
    try {
        if (!(o.trainFraction > 0.f && o.trainFraction <= 1.f))
            throw std::runtime_error("--train-fraction must be in (0, 1]");
        const std::vector<TruthRow> truth = loadTruth(o.truth);
        CardEvalSettings settings;
        const std::vector<TrackedFrame> tracked =
            runCardTracker(o, truth.size(), settings.frameSize);
        if (!o.perFrameCsv.empty())
            writePerFrame(o.perFrameCsv, truth, tracked, settings);
        const CardMetrics m = computeCardMetrics(truth, tracked, settings);
        std::fprintf(out, "card eval: %s (%dx%d), truth %s; frame 0 trains (central %.2f)%s\n",
                     o.video.c_str(), settings.frameSize.width, settings.frameSize.height,
                     o.truth.c_str(), static_cast<double>(o.trainFraction),
                     o.deinterlace ? "; deinterlaced" : "");
        std::fputs(cardReport(m).c_str(), out);
        std::fprintf(out, "%s\n", cardSummaryLine(m).c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(err, "mirror-eval card: %s\n", e.what());
        return 1;
    }
}

}  // namespace mirror_eval
