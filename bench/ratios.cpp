#include "ratios.hpp"

#include "card_tracker_case.hpp"
#include "chromaticity_cases.hpp"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <functional>
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
    // Batch sizes from a short warm-up, so each sample is ~5 ms whatever the contender's speed.
    for (auto& c : contenders) {
        const double start = cpuMs();
        int calls = 0;
        while (cpuMs() - start < 20.0) {
            c.run();
            ++calls;
        }
        c.batch = std::max(1, static_cast<int>(calls * kBatchMs / (cpuMs() - start)));
    }
    // Rounds interleave the contenders, so clock or cache drift hits all of them alike.
    for (int round = 0; round < kRounds; ++round) {
        for (auto& c : contenders) {
            const double start = cpuMs();
            for (int i = 0; i < c.batch; ++i)
                c.run();
            c.perCallMs.push_back((cpuMs() - start) / c.batch);
        }
    }
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

}  // namespace bench
