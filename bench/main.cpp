// mirror-bench: ours side by side with the peers, on one core, 720x480. Without --ratios it is a
// normal Google Benchmark binary (every --benchmark_* flag works); with --ratios it times the
// target pairs of issue 3 itself and prints one `ratio <name> <value>` line per target.
//
// Own flags (removed before Google Benchmark sees the command line):
//   --ratios        print raw times and the target ratios, then exit
//   --image=PATH    the photograph the frames are made from (default: ../shared/data astronaut)

#include "bench_setup.hpp"
#include "card_tracker_case.hpp"
#include "chromaticity_cases.hpp"
#include "ratios.hpp"

#include <benchmark/benchmark.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace {

constexpr int kCardFrames = 90;

void registerChromaticity(bench::ChromaticityCases& cases)
{
    const double frameBytes = static_cast<double>(cases.frame().total() * cases.frame().elemSize());
    auto add = [frameBytes](const std::string& name, std::function<void()> run) {
        benchmark::RegisterBenchmark(name.c_str(), [run, frameBytes](benchmark::State& state) {
            for (auto _ : state) {
                run();
                benchmark::ClobberMemory();
            }
            state.SetBytesProcessed(
                static_cast<std::int64_t>(frameBytes * static_cast<double>(state.iterations())));
        })->Unit(benchmark::kMicrosecond);
    };
    auto call = [&cases](void (bench::ChromaticityCases::*method)()) {
        return [&cases, method] { (cases.*method)(); };
    };
    add("chroma/memcpy_frame", call(&bench::ChromaticityCases::memcpyFrame));
    add("chroma/opencv_table1", call(&bench::ChromaticityCases::table1OpenCv));
    add("chroma/opencv_float_divide", call(&bench::ChromaticityCases::floatDivideOpenCv));
    add("chroma/opencv_float_reciprocal", call(&bench::ChromaticityCases::floatReciprocalOpenCv));
    add("chroma/seed_table5_lut", call(&bench::ChromaticityCases::seedTable5));
    add("chroma/ours", call(&bench::ChromaticityCases::ours));
    for (auto path : bench::ChromaticityCases::concretePaths())
        add(std::string("chroma/ours_") + vision::chromaticityPathName(path),
            [&cases, path] { cases.oursOn(path); });
}

void registerCardTracker(const cv::Mat& photo)
{
    benchmark::RegisterBenchmark("card_tracker/chroma_and_process", [&photo](
                                                                        benchmark::State& state) {
        // Made on first use: a filter that skips this benchmark does not pay for the frames.
        static std::unique_ptr<bench::CardTrackerCase> card;
        if (!card)
            card = std::make_unique<bench::CardTrackerCase>(photo, kCardFrames);
        card->restart();
        int frames = 0, tracked = 0;
        for (auto _ : state) {
            if (!card->step()) {
                state.PauseTiming();
                frames += card->processedFrames();
                tracked += card->trackedFrames();
                card->restart();
                state.ResumeTiming();
                card->step();
            }
        }
        frames += card->processedFrames();
        tracked += card->trackedFrames();
        state.counters["tracked_share"] = frames ? static_cast<double>(tracked) / frames : 0.0;
    })->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv)
{
    bool ratios = false;
    std::string image;
    std::vector<char*> args{argv[0]};
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--ratios") == 0)
            ratios = true;
        else if (std::strncmp(argv[i], "--image=", 8) == 0)
            image = argv[i] + 8;
        else
            args.push_back(argv[i]);
    }

    try {
        const int cpu = bench::pinToLowestCpu();
        if (cpu < 0) {
            std::fprintf(stderr, "mirror-bench: cannot pin to one CPU: %s\n", std::strerror(errno));
            return 1;
        }
        cv::setNumThreads(1);  // OpenCV would otherwise spread its calls over worker threads
        const std::string photo = bench::findPhoto(image);
        if (photo.empty()) {
            std::fprintf(stderr,
                         "mirror-bench: no photograph found (looked for ../shared/data/"
                         "debian_skimage_faces/astronaut.png and opencv-doc's fruits.jpg);"
                         " pass --image=PATH\n");
            return 1;
        }
        const cv::Mat frame = bench::loadFrame(photo);
        std::printf(
            "mirror-bench: pinned to CPU %d (the lowest allowed), one thread, OpenCV "
            "threads 1\n",
            cpu);
        std::printf("mirror-bench: frame %dx%d BGR24 from %s\n", frame.cols, frame.rows,
                    photo.c_str());

        bench::ChromaticityCases chroma(frame);
        if (!chroma.checkExactness()) {
            std::fprintf(stderr, "mirror-bench: an exact formulation is not exact on the frame\n");
            return 1;
        }
        std::fflush(stdout);

        if (ratios) {
            bench::CardTrackerCase card(frame, kCardFrames);
            bench::printRatios(chroma, card);
            return 0;
        }

        registerChromaticity(chroma);
        registerCardTracker(frame);
        int benchArgc = static_cast<int>(args.size());
        benchmark::AddCustomContext("pinned_cpu", std::to_string(cpu));
        benchmark::AddCustomContext("frame", photo + " -> 720x480 BGR24");
        benchmark::Initialize(&benchArgc, args.data());
        if (benchmark::ReportUnrecognizedArguments(benchArgc, args.data()))
            return 2;
        benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}
