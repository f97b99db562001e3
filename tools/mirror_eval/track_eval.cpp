#include "track_eval.hpp"

#include "detect_eval.hpp"
#include "error_stats.hpp"
#include "face_match.hpp"
#include "face_sequence.hpp"
#include "face_truth.hpp"
#include "vision/face_stage.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/motion_stage.hpp"
#include "vision/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

namespace mirror_eval {

namespace {

struct Config {
    const char* name;
    vision::FaceTrackingMode mode;
    bool motionMask;
};

constexpr Config kConfigs[] = {
    {"detector", vision::FaceTrackingMode::None, false},
    {"motion", vision::FaceTrackingMode::None, true},
    {"translation", vision::FaceTrackingMode::Translation, true},
    {"similarity", vision::FaceTrackingMode::Similarity, true},
};

const char* describe(const Config& c)
{
    switch (c.mode) {
        case vision::FaceTrackingMode::None:
            return c.motionMask ? "+ motion mask (masked scan), no tracking"
                                : "detector only: full scan every frame, no tracking";
        case vision::FaceTrackingMode::Translation:
            return "+ translation tracking (LK corners), motion mask";
        default:
            return "+ similarity tracking, roll-warped verification, motion mask";
    }
}

/// Fraction of 255 pixels of a mask (frame / downscale) inside a frame-coordinate box.
double maskFraction(const vision::ConstImageView& mask, const BoxF& box, int downscale)
{
    const float k = static_cast<float>(downscale);
    const int x0 = std::max(0, static_cast<int>(box.x / k));
    const int y0 = std::max(0, static_cast<int>(box.y / k));
    const int x1 = std::min(mask.width, static_cast<int>((box.x + box.width) / k));
    const int y1 = std::min(mask.height, static_cast<int>((box.y + box.height) / k));
    long on = 0, all = 0;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            on += mask.row(y)[x] != 0;
            ++all;
        }
    }
    return all > 0 ? static_cast<double>(on) / static_cast<double>(all) : 0.0;
}

struct Previous {
    int truthId = -1;
    long frame = -1;
    double dx = 0.0, dy = 0.0;
};

TrackScore runConfig(const Config& config, const FaceSequence& seq,
                     const vision::HaarCascade& cascade, const TrackEvalOptions& o, std::FILE* out)
{
    // Frames are decoded one at a time (a long sequence does not fit in memory decoded).
    cv::Mat image = cv::imread(seq.frames.front(), cv::IMREAD_COLOR);
    if (image.empty())
        throw std::runtime_error("frame " + seq.frames.front() + ": cannot decode");
    const vision::Size frameSize{image.cols, image.rows};

    vision::MotionStageOptions mopt;
    mopt.downscale = o.downscale;
    vision::MotionStage motion(frameSize, mopt);
    vision::FaceTrackerOptions topt;
    topt.mode = config.mode;
    topt.useMotionMask = config.motionMask;
    topt.detector.minSize = {o.minSize, o.minSize};
    topt.livenessBySway = !o.noSway;
    // Detector-only configurations show a face only in a frame whose scan completed: a scan
    // spread over frames would leave them blank in between.
    topt.detectionWindowBudget = config.mode == vision::FaceTrackingMode::None ? 0 : o.budget;
    vision::FaceStage faceStage(motion, cascade, topt);

    TrackScore score;
    score.config = config.name;
    std::map<int, Previous> previous;  // by track id
    vision::FrameState state;
    for (std::size_t k = 0; k < seq.frames.size(); ++k) {
        if (k > 0) {
            image = cv::imread(seq.frames[k], cv::IMREAD_COLOR);
            if (image.empty())
                throw std::runtime_error("frame " + seq.frames[k] + ": cannot decode");
            if (image.cols != frameSize.width || image.rows != frameSize.height)
                throw std::runtime_error("frame " + seq.frames[k] + ": size differs from frame 0");
        }
        vision::Frame frame;
        frame.image = {image.data, image.cols, image.rows, static_cast<int>(image.step),
                       vision::PixelFormat::BGR24};
        frame.sequence = k;
        frame.timestampNs = static_cast<std::int64_t>(k) * 40'000'000;
        vision::Pipeline::begin(state, frame);
        motion.process(state);
        faceStage.process(state);

        std::vector<const vision::TrackedFace*> shown;
        std::vector<BoxF> shownBoxes;
        for (const vision::TrackedFace& f : faceStage.faces()) {
            if (f.shown()) {
                shown.push_back(&f);
                // Landmark truth: our square as the box its face's landmarks would have.
                shownBoxes.push_back(seq.composed
                                         ? squareAbout(f.centre, f.size)
                                         : landmarkConventionBox(f.centre, f.size, f.rollDegrees));
            }
        }
        const std::vector<TruthFace>& truth = seq.truth[k];
        std::vector<BoxF> truthBoxes;
        for (const TruthFace& t : truth)
            truthBoxes.push_back(t.box);
        const Pairing p = pairByIou(shownBoxes, truthBoxes, o.minIou);
        if (seq.composed && k >= 30 && motion.ok()) {
            for (const TruthFace& t : truth)
                (t.moving ? score.movingMaskFractions : score.staticMaskFractions)
                    .push_back(maskFraction(motion.mask(), t.box, motion.downscale()));
        }
        if (o.perFrame) {
            std::fprintf(out, "%s %zu:", config.name, k);
            for (const TruthFace& t : truth)
                std::fprintf(out, " truth[%d%s %.0f,%.0f %.0fx%.0f roll %.1f]", t.id,
                             t.moving ? "" : " static", static_cast<double>(t.centre.x),
                             static_cast<double>(t.centre.y), static_cast<double>(t.box.width),
                             static_cast<double>(t.box.height), t.rollDegrees);
            for (const vision::TrackedFace& f : faceStage.faces())
                std::fprintf(out, " face[%d %s %.0f,%.0f %.0f roll %.1f hits %d misses %d]", f.id,
                             f.shown() ? "shown" : "tentative", static_cast<double>(f.centre.x),
                             static_cast<double>(f.centre.y), static_cast<double>(f.size),
                             static_cast<double>(f.rollDegrees), f.hits, f.misses);
            for (std::size_t c = 0; c < shown.size(); ++c) {
                float best = 0.f;
                for (const BoxF& t : truthBoxes)
                    best = std::max(best, iou(shownBoxes[c], t));
                std::fprintf(out, " iou(%d)=%.2f", shown[c]->id, static_cast<double>(best));
            }
            std::fputc('\n', out);
        }

        for (std::size_t c = 0; c < shown.size(); ++c) {
            int ti = p.truthOfCandidate[c];
            if (ti < 0) {
                // A face entering or leaving: the detector boxes the part in view.
                for (std::size_t u = 0; u < truth.size() && ti < 0; ++u) {
                    const TruthFace& t = truth[u];
                    if (t.moving && p.candidateOfTruth[u] < 0 && !wholeInFrame(t.box, frameSize) &&
                        iou(shownBoxes[c], partInView(t.box, frameSize)) >= o.minIou)
                        ti = static_cast<int>(u);
                }
            }
            if (ti >= 0 && truth[static_cast<std::size_t>(ti)].moving &&
                !wholeInFrame(truth[static_cast<std::size_t>(ti)].box, frameSize)) {
                ++score.partlyInView;
                previous.erase(shown[c]->id);
                continue;
            }
            if (ti < 0 || !truth[static_cast<std::size_t>(ti)].moving) {
                ++score.falsePositives;
                score.falsePositivesOnStatic += ti >= 0;
                previous.erase(shown[c]->id);
                continue;
            }
            const TruthFace& t = truth[static_cast<std::size_t>(ti)];
            ++score.truePositives;
            score.ious.push_back(iou(shownBoxes[c], t.box));
            if (!seq.composed)
                score.eyeRollErrors.push_back(std::fabs(shown[c]->rollDegrees - t.eyeRollDegrees));
            double err = std::fabs(shown[c]->rollDegrees - t.rollDegrees);
            score.rollErrors.push_back(err);
            const double dx = shown[c]->centre.x - t.centre.x;
            const double dy = shown[c]->centre.y - t.centre.y;
            Previous& prev = previous[shown[c]->id];
            if (prev.truthId == t.id && prev.frame == static_cast<long>(k) - 1)
                score.centreSteps.push_back(std::hypot(dx - prev.dx, dy - prev.dy));
            prev = {t.id, static_cast<long>(k), dx, dy};
        }
        for (std::size_t ti = 0; ti < truth.size(); ++ti) {
            const TruthFace& t = truth[ti];
            if (!t.moving || p.candidateOfTruth[ti] >= 0)
                continue;
            score.falseNegatives += wholeInFrame(t.box, frameSize);
        }
        ++score.frames;
    }
    score.sceneCuts = faceStage.cuts();
    return score;
}

std::string orDash(bool show, double v, const char* format)
{
    if (!show)
        return "-";
    char text[32];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

}  // namespace

double TrackScore::precision() const
{
    const long shown = truePositives + falsePositives;
    return shown > 0 ? static_cast<double>(truePositives) / static_cast<double>(shown) : 1.0;
}

double TrackScore::recall() const
{
    const long faces = truePositives + falseNegatives;
    return faces > 0 ? static_cast<double>(truePositives) / static_cast<double>(faces) : 1.0;
}

double TrackScore::rollMeanError() const
{
    return meanOf(rollErrors);
}
double TrackScore::jitterMean() const
{
    return meanOf(centreSteps);
}

int runTrackEval(const TrackEvalOptions& o, std::FILE* out, std::FILE* err)
{
    try {
        std::vector<Config> configs;
        for (const Config& c : kConfigs) {
            if (o.config == "all" || o.config == c.name)
                configs.push_back(c);
        }
        if (configs.empty())
            throw std::runtime_error("--config '" + o.config +
                                     "': expected detector, motion, translation, similarity or "
                                     "all");
        if (o.downscale < 1 || o.downscale > 4)
            throw std::runtime_error("--downscale must be in 1..4");
        if (!(o.minIou > 0.f && o.minIou <= 1.f))
            throw std::runtime_error("--min-iou must be in (0, 1]");
        if (o.budget < 0)
            throw std::runtime_error("--budget must be >= 0");
        if (o.start < 0)
            throw std::runtime_error("--start must be >= 0");
        const FaceSequence seq = loadFaceSequence(o.frames, o.truth, o.start, o.maxFrames);
        const std::string cascadePath = o.cascade.empty() ? kDefaultCascade : o.cascade;
        const vision::HaarCascade cascade = vision::loadHaarCascade(cascadePath);

        long truthFaces = 0, staticFaces = 0;
        for (const auto& frame : seq.truth) {
            truthFaces += static_cast<long>(frame.size());
            for (const auto& t : frame)
                staticFaces += !t.moving;
        }
        std::fprintf(out,
                     "track eval: %zu frames of %s from frame %d (a cold start), truth %s (%s, "
                     "%ld truth faces, %ld of them static); cascade %s\n",
                     seq.frames.size(), o.frames.c_str(), o.start, o.truth.c_str(),
                     seq.composed ? "composed multi-face" : "FGNet 68-point", truthFaces,
                     staticFaces, cascadePath.c_str());
        std::fprintf(out,
                     "pipeline: MotionStage (frame / %d) + FaceStage, detector windows per frame "
                     "%s,%s tracker defaults otherwise; shown faces = TrackedFace::shown()\n",
                     o.downscale,
                     o.budget > 0
                         ? (std::to_string(o.budget) + " (tracking configurations)").c_str()
                         : "unlimited",
                     o.noSway ? " no LivenessCue (--no-sway)," : "");
        std::fprintf(
            out,
            "match: IoU(%s) >= %.2f, one to one, highest first; "
            "unmatched shown faces%s are false positives; %s\n",
            seq.composed
                ? "our square box, the truth square of `size` about (cx, cy)"
                : ("our box, the landmarks' bounding box; our box: " + landmarkBoxText()).c_str(),
            static_cast<double>(o.minIou), seq.composed ? " and shown faces on static faces" : "",
            seq.composed ? "a moving face wholly in the frame and unmatched is a false "
                           "negative; a moving face partly out of view is optional: a "
                           "shown face on it (IoU with its box or with its part in view) "
                           "is neither a true nor a false positive (column 'part')"
                         : "a frame without a match is a false negative");
        std::fprintf(out,
                     "roll error: |our roll - truth roll| over true positives (%s); jitter: mean "
                     "|(our centre - truth centre) change| between consecutive frames of a "
                     "track on the same face, px\n",
                     seq.composed ? "truth roll as given"
                                  : "truth roll: the best line through eye midpoint, nose tip and "
                                    "mouth centre; 'eye' column: against the eye line's roll");
        for (const Config& c : configs)
            std::fprintf(out, "  %-12s %s\n", c.name, describe(c));

        std::vector<TrackScore> scores;
        for (const Config& c : configs)
            scores.push_back(runConfig(c, seq, cascade, o, out));

        std::fprintf(out, "%-12s %7s %6s %6s %7s %5s %9s %7s %9s %9s %9s %8s\n", "config", "TP",
                     "FP", seq.composed ? "FP_st" : "-", "FN", "part", "precision", "recall",
                     "roll_err", seq.composed ? "-" : "eye_err", "jitter_px", "mean_iou");
        for (std::size_t i = 0; i < scores.size(); ++i) {
            const TrackScore& s = scores[i];
            const bool roll = configs[i].mode == vision::FaceTrackingMode::Similarity;
            std::fprintf(out, "%-12s %7ld %6ld %6s %7ld %5ld %9.4f %7.4f %9s %9s %9.2f %8.3f\n",
                         s.config.c_str(), s.truePositives, s.falsePositives,
                         seq.composed ? std::to_string(s.falsePositivesOnStatic).c_str() : "-",
                         s.falseNegatives, s.partlyInView, s.precision(), s.recall(),
                         orDash(roll, s.rollMeanError(), "%.2f").c_str(),
                         orDash(roll && !seq.composed, meanOf(s.eyeRollErrors), "%.2f").c_str(),
                         s.jitterMean(), meanOf(s.ious));
        }
        if (seq.composed && !scores.front().staticMaskFractions.empty())
            std::fprintf(out,
                         "motion mask (from frame 30): foreground fraction inside static faces "
                         "%.3f, inside moving faces %.3f\n",
                         meanOf(scores.front().staticMaskFractions),
                         meanOf(scores.front().movingMaskFractions));
        const TrackScore& last = scores.back();
        std::fprintf(out, "scene cuts (tracks dropped, the whole frame scanned): %ld\n",
                     last.sceneCuts);
        std::fprintf(out, "track: precision=%.4f recall=%.4f roll_mean_err_deg=%.2f\n",
                     last.precision(), last.recall(), last.rollMeanError());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(err, "mirror-eval track: %s\n", e.what());
        return 1;
    }
}

}  // namespace mirror_eval
