#include "ratios.hpp"

#include "card_tracker_case.hpp"
#include "chromaticity_cases.hpp"
#include "dlib_peer.hpp"
#include "face_cases.hpp"
#include "overlay_render_case.hpp"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

namespace {

// Thread CPU time, not wall time: this machine (and CI) runs other jobs on the same core now and
// then, and time spent descheduled is not ours. On a quiet machine the two agree.
double cpuMs()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

struct Contender {
    std::string name;
    std::function<void()> run;
    int batch = 1;                  ///< calls per timed batch (about kBatchMs)
    std::vector<double> perCallMs;  ///< one sample per round
};

/// The contenders the ratios use, in the order they are listed.
enum : std::size_t { kMemcpy, kTable1, kFloatDivide, kFloatReciprocal, kSeedLut, kOurs };

constexpr double kBatchMs = 5.0;
constexpr int kRounds = 61;
constexpr int kFaceRounds = 21;    // the face contenders take 1-50 ms a call
constexpr int kRenderFrames = 61;  // of each kind; ~10-20 ms a 1280x720 frame on one core

/// Times the contenders: batch sizes (calls per ~kBatchMs) from a short warm-up, then `rounds`
/// rounds that interleave them, so clock or cache drift hits all of them alike. One per-call
/// sample per round in perCallMs.
void timeInterleaved(std::vector<Contender>& contenders, int rounds)
{
    for (auto& c : contenders) {
        const double start = cpuMs();
        int calls = 0;
        while (cpuMs() - start < 20.0) {
            c.run();
            ++calls;
        }
        c.batch = std::max(1, static_cast<int>(calls * kBatchMs / (cpuMs() - start)));
    }
    for (int round = 0; round < rounds; ++round) {
        for (auto& c : contenders) {
            const double start = cpuMs();
            for (int i = 0; i < c.batch; ++i)
                c.run();
            c.perCallMs.push_back((cpuMs() - start) / c.batch);
        }
    }
}

}  // namespace

void printRatios(ChromaticityCases& chroma, CardTrackerCase& card)
{
    auto call = [&chroma](void (ChromaticityCases::*method)()) {
        return [&chroma, method] { (chroma.*method)(); };
    };
    // The six the ratios use (kMemcpy..kOurs), then each of our concrete paths for reference.
    std::vector<Contender> contenders;
    contenders.push_back({"memcpy_frame", call(&ChromaticityCases::memcpyFrame), 1, {}});
    contenders.push_back({"opencv_table1", call(&ChromaticityCases::table1OpenCv), 1, {}});
    contenders.push_back(
        {"opencv_float_divide", call(&ChromaticityCases::floatDivideOpenCv), 1, {}});
    contenders.push_back(
        {"opencv_float_reciprocal", call(&ChromaticityCases::floatReciprocalOpenCv), 1, {}});
    contenders.push_back({"seed_table5_lut", call(&ChromaticityCases::seedTable5), 1, {}});
    contenders.push_back({std::string("ours (best = ") +
                              vision::chromaticityPathName(vision::bestChromaticityPath()) + ")",
                          call(&ChromaticityCases::ours),
                          1,
                          {}});
    for (auto path : ChromaticityCases::concretePaths())
        contenders.push_back({std::string("ours_") + vision::chromaticityPathName(path),
                              [&chroma, path] { chroma.oursOn(path); },
                              1,
                              {}});
    timeInterleaved(contenders, kRounds);
    std::vector<double> ms;
    for (const auto& c : contenders) {
        ms.push_back(median(c.perCallMs));
        std::printf("time chroma_%-24s %8.4f ms  (median of %d rounds x %d calls)\n",
                    c.name.c_str(), ms.back(), kRounds, c.batch);
    }
    const double ours = ms[kOurs];
    const double opencvExact =
        std::min(ms[kFloatDivide], ms[kFloatReciprocal]);  // peer at its best

    std::vector<double> frameMs;
    int passes = 0, tracked = 0, processed = 0;
    double errorSum = 0.0;
    const double start = cpuMs();
    while (passes < 5 || (passes < 40 && cpuMs() - start < 3000.0)) {
        card.restart();  // untimed: training on frame 0
        for (;;) {
            const double t0 = cpuMs();
            if (!card.step())
                break;
            frameMs.push_back(cpuMs() - t0);
        }
        ++passes;
        processed += card.processedFrames();
        tracked += card.trackedFrames();
        errorSum += card.meanCornerErrorPx() * card.trackedFrames();
    }
    const double cardMs = median(frameMs);
    std::sort(frameMs.begin(), frameMs.end());
    std::printf(
        "time card_tracker_frame %8.4f ms median, %.4f ms p90  (%zu frames, %d passes;"
        " tracking %d/%d frames, mean corner error %.2f px)\n",
        cardMs, frameMs[frameMs.size() * 9 / 10], frameMs.size(), passes, tracked, processed,
        tracked ? errorSum / tracked : 0.0);

    std::printf("ratio chroma_vs_opencv_exact %.2f\n", opencvExact / ours);
    std::printf("ratio chroma_vs_seed_lut %.2f\n", ms[kSeedLut] / ours);
    std::printf("ratio card_tracker_ms %.3f\n", cardMs);
}

namespace {

// p99: the smallest value at least 99% of the samples do not exceed.
double percentile99(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : v[std::min(n - 1, (n * 99 + 99) / 100 - 1)];
}

// dlib's 68-point shape predictor on the faces our fit started from (every kDlibEvery-th frame
// with fits, the frame's full-resolution grey, decoding and conversion untimed): ms per face.
// A frame the AAM fitted and the boxes its fits started from.
struct FittedFrame {
    int frame;
    std::vector<cv::Rect> boxes;
};

double dlibMsPerFace(FaceCases& faces, const std::vector<FittedFrame>& fitted)
{
    constexpr std::size_t kDlibEvery = 5;
    mirror_eval::DlibPeer dlib;
    std::vector<double> perFace;
    for (std::size_t k = 0; k < fitted.size(); k += kDlibEvery) {
        faces.pipelineLoad(fitted[k].frame);
        cv::Mat grey;
        cv::cvtColor(faces.pipelineFrame(), grey, cv::COLOR_BGR2GRAY);
        for (const cv::Rect& r : fitted[k].boxes) {
            const mirror_eval::FaceBoxPx box{static_cast<double>(r.x), static_cast<double>(r.y),
                                             static_cast<double>(r.x + r.width),
                                             static_cast<double>(r.y + r.height)};
            const double t0 = cpuMs();
            const auto points = dlib.landmarks(grey, box);
            perFace.push_back(cpuMs() - t0);
            if (points.size() != 68)
                throw std::runtime_error("mirror-bench: dlib's predictor gave no 68 points");
        }
    }
    double mean = 0.0;
    for (const double t : perFace)
        mean += t / static_cast<double>(perFace.size());
    return mean;
}

// The pipeline: every FGNet frame once, in order, decoding untimed; the motion and face stages
// timed apart from the AAM fit, then dlib's predictor on the same faces.
void printPipelineRatios(FaceCases& faces)
{
    std::vector<double> frameMs;
    double aamMs = 0.0;
    long fits = 0, iterations = 0;
    std::vector<FittedFrame> fitted;
    faces.pipelineRestart();
    int shownFrames = 0;
    for (int i = 0; i < faces.pipelineFrames(); ++i) {
        faces.pipelineLoad(i);
        const double t0 = cpuMs();
        faces.pipelineStep();
        const double t1 = cpuMs();
        faces.pipelineStepAam();
        const double t2 = cpuMs();
        frameMs.push_back(t2 - t0);
        shownFrames += faces.pipelineShownFaces() > 0;
        if (faces.pipelineFitsRun() > 0) {
            aamMs += t2 - t1;
            fits += faces.pipelineFitsRun();
            iterations += faces.pipelineFitIterations();
            fitted.push_back({i, faces.pipelineShownBoxes()});
        }
    }
    double mean = 0.0;
    for (const double t : frameMs)
        mean += t / static_cast<double>(frameMs.size());
    const double p99 = percentile99(frameMs);
    std::vector<double> sorted = frameMs;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    std::printf(
        "time face_pipeline_frame %.3f ms mean, %.3f ms median, %.3f ms p99, %.3f ms max"
        "  (%zu FGNet 720x576 frames of %s, motion /2 + faces%s; a face shown in %d)\n",
        mean, n ? sorted[n / 2] : 0.0, p99, n ? sorted.back() : 0.0, n, faces.imageDir().c_str(),
        faces.hasAam() ? " + aam" : "", shownFrames);
    std::printf("ratio face_pipeline_mean_ms %.3f\n", mean);
    std::printf("ratio face_pipeline_p99_ms %.3f\n", p99);
    if (!faces.hasAam()) {
        std::printf("info aam: no model at %s (scripts/dev model builds it): no AAM lines\n",
                    faces.aamModelPath().c_str());
        return;
    }
    if (fits == 0)
        throw std::runtime_error("mirror-bench: the AAM stage fitted no face on FGNet");
    const double oursPerFace = aamMs / static_cast<double>(fits);
    const double dlibPerFace = dlibMsPerFace(faces, fitted);
    std::printf("time aam_fit_per_face %.3f ms (%ld fits in %zu frames, model %s)\n", oursPerFace,
                fits, fitted.size(), faces.aamModelPath().c_str());
    std::printf("time dlib_shape_predictor_per_face %.3f ms (same boxes, every 5th frame fitted)\n",
                dlibPerFace);
    std::printf("ratio aam_ms_per_face %.3f\n", oursPerFace);
    std::printf("ratio aam_iters_per_frame %.2f\n",
                static_cast<double>(iterations) / static_cast<double>(fits));
    std::printf("ratio aam_vs_dlib %.2f\n", dlibPerFace / oursPerFace);
}

}  // namespace

void printFaceRatios(FaceCases& faces)
{
    // Pairs: ours then the peer, per cascade, then motion, then flow.
    std::vector<Contender> contenders;
    for (int i = 0; i < faces.cascadeCount(); ++i) {
        contenders.push_back(
            {"vj_ours_" + faces.cascadeName(i), [&faces, i] { faces.detectOurs(i); }, 1, {}});
        contenders.push_back(
            {"vj_opencv_" + faces.cascadeName(i), [&faces, i] { faces.detectOpenCv(i); }, 1, {}});
    }
    const std::size_t motionAt = contenders.size();
    contenders.push_back({"mog_ours_k3", [&faces] { faces.motionOurs(); }, 1, {}});
    contenders.push_back({"mog_opencv_mog2_k3", [&faces] { faces.motionOpenCv(); }, 1, {}});
    const std::size_t flowAt = contenders.size();
    for (int r = 0; r < FaceCases::kFlowResolutions; ++r) {
        const std::string res = FaceCases::flowResolutionName(r);
        contenders.push_back(
            {"lk_ours_50pts_3levels_" + res, [&faces, r] { faces.flowOurs(r); }, 1, {}});
        contenders.push_back(
            {"lk_opencv_50pts_3levels_" + res, [&faces, r] { faces.flowOpenCv(r); }, 1, {}});
    }
    timeInterleaved(contenders, kFaceRounds);
    std::vector<double> ms;
    for (const auto& c : contenders) {
        ms.push_back(median(c.perCallMs));
        std::printf("time %-50s %8.4f ms  (median of %d rounds x %d calls)\n", c.name.c_str(),
                    ms.back(), kFaceRounds, c.batch);
    }
    for (int i = 0; i < faces.cascadeCount(); ++i) {
        std::printf("faces %s at 360x240: ours %d, opencv %d\n", faces.cascadeName(i).c_str(),
                    faces.detectOurs(i), faces.detectOpenCv(i));
    }
    for (int r = 0; r < FaceCases::kFlowResolutions; ++r) {
        std::printf("flow points tracked at %s: ours %d, opencv %d of %d\n",
                    FaceCases::flowResolutionName(r), faces.flowOurs(r), faces.flowOpenCv(r),
                    FaceCases::kFlowPoints);
    }

    std::printf("ratio vj_vs_opencv %.2f\n", ms[1] / ms[0]);
    for (int i = 1; i < faces.cascadeCount(); ++i) {
        const auto k = static_cast<std::size_t>(2 * i);
        std::printf("info vj_vs_opencv_%s %.2f\n", faces.cascadeName(i).c_str(), ms[k + 1] / ms[k]);
    }
    std::printf("ratio mog_vs_mog2 %.2f\n", ms[motionAt + 1] / ms[motionAt]);
    std::printf("ratio lk_vs_opencv %.2f\n", ms[flowAt + 1] / ms[flowAt]);
    for (int r = 1; r < FaceCases::kFlowResolutions; ++r) {
        const auto k = flowAt + static_cast<std::size_t>(2 * r);
        std::printf("info lk_vs_opencv_%s %.2f\n", FaceCases::flowResolutionName(r),
                    ms[k + 1] / ms[k]);
    }
    printPipelineRatios(faces);
}

void printRenderRatios(const std::string& catalogueToml)
{
    OverlayRenderCase render(catalogueToml);
    if (!render.frame(true))
        throw std::runtime_error(std::string("mirror-bench: overlay frame failed: ") +
                                 render.lastError());
    const OverlayRenderCase::Timing t = render.measure(kRenderFrames);
    std::printf(
        "time render_frame_1280x720 %.3f ms with 3 faces' overlays, %.3f ms without"
        "  (median thread CPU of %d frames each, llvmpipe LP_NUM_THREADS=0; overlays %s,"
        " %d triangles)\n",
        t.withMs, t.withoutMs, kRenderFrames, render.overlayNames().c_str(), t.triangles);
    std::printf("ratio render_3faces_ms %.3f\n", t.addedMs());
}

}  // namespace bench
