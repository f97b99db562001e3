// mirror-bench: ours side by side with the peers, on one core. Without --ratios it is a normal
// Google Benchmark binary (every --benchmark_* flag works); with --ratios it times the target
// pairs (chromaticity and card, faces) and the overlays' cost itself and prints one
// `ratio <name> <value>` line per target.
//
// Own flags (removed before Google Benchmark sees the command line):
//   --ratios        print raw times and the target ratios, then exit
//   --ratios=chroma only chromaticity and the card tracker; --ratios=faces only the faces;
//   --ratios=render only the 3D overlays of 3 faces (headless GL)
//   --image=PATH    the photograph the frames are made from (default: ../shared/data astronaut)
//   --overlays=PATH the overlay catalogue --ratios times (default: assets/overlays/catalogue.toml)

#include "bench_setup.hpp"
#include "card_tracker_case.hpp"
#include "chromaticity_cases.hpp"
#include "face_cases.hpp"
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

// Made on first use: a filter that skips the face benchmarks does not decode their frames (and a
// board without the shared data can still run the others).
bench::FaceCases& faceCases()
{
    static std::unique_ptr<bench::FaceCases> cases;
    if (!cases)
        cases = std::make_unique<bench::FaceCases>();
    return *cases;
}

void registerFaces()
{
    auto add = [](const std::string& name, std::function<void(bench::FaceCases&)> run) {
        benchmark::RegisterBenchmark(name.c_str(), [run](benchmark::State& state) {
            bench::FaceCases* cases = nullptr;
            try {
                cases = &faceCases();
            } catch (const std::exception& e) {
                state.SkipWithError(e.what());
                return;
            }
            for (auto _ : state) {
                run(*cases);
                benchmark::ClobberMemory();
            }
        })->Unit(benchmark::kMillisecond);
    };
    // Cascade names are known without loading anything: the order of FaceCases.
    const char* const cascades[] = {"default", "alt2"};
    for (int i = 0; i < 2; ++i) {
        add(std::string("faces/vj_ours_360x240/") + cascades[i],
            [i](bench::FaceCases& c) { c.detectOurs(i); });
        add(std::string("faces/vj_opencv_360x240/") + cascades[i],
            [i](bench::FaceCases& c) { c.detectOpenCv(i); });
    }
    add("motion/mog_ours_360x240_k3", [](bench::FaceCases& c) { c.motionOurs(); });
    add("motion/mog2_opencv_360x240_k3", [](bench::FaceCases& c) { c.motionOpenCv(); });
    for (int r = 0; r < bench::FaceCases::kFlowResolutions; ++r) {
        const std::string res = bench::FaceCases::flowResolutionName(r);
        add("flow/lk_ours_50pts_3levels/" + res, [r](bench::FaceCases& c) { c.flowOurs(r); });
        add("flow/lk_opencv_50pts_3levels/" + res, [r](bench::FaceCases& c) { c.flowOpenCv(r); });
    }
    benchmark::RegisterBenchmark("faces/pipeline_fgnet_720x576", [](benchmark::State& state) {
        bench::FaceCases* cases = nullptr;
        try {
            cases = &faceCases();
        } catch (const std::exception& e) {
            state.SkipWithError(e.what());
            return;
        }
        // Frames in order, decoding untimed; the sequence restarts (fresh stages) at its end.
        cases->pipelineRestart();
        int next = 0, shown = 0, frames = 0;
        for (auto _ : state) {
            state.PauseTiming();
            if (next == cases->pipelineFrames()) {
                cases->pipelineRestart();
                next = 0;
            }
            cases->pipelineLoad(next++);
            state.ResumeTiming();
            cases->pipelineStep();
            ++frames;
            shown += cases->pipelineShownFaces() > 0;
        }
        state.counters["face_shown_share"] = frames ? static_cast<double>(shown) / frames : 0.0;
    })->Unit(benchmark::kMillisecond);
}

const char* const kUsage = R"(usage: mirror-bench [--ratios[=chroma|faces|render]] [--image=PATH]
                    [--overlays=CATALOGUE] [--benchmark_...] [--help] [--version]

Our vision code beside its peers (OpenCV, the dissertation's own code), in one run on one core.
Before any timing, each chromaticity formulation is checked for exactness on the frame.

  --ratios             every target as ours/peer ratios (chroma, faces, render), about 45 s
  --ratios=chroma      only the card's colour cases; --ratios=faces, --ratios=render likewise
  --image=PATH         make the 720x480 frames from this photograph (default: the shared data's
                       astronaut.png, else opencv-doc's fruits.jpg)
  --overlays=FILE      the overlay catalogue for the render case
  --benchmark_...      any Google Benchmark flag, e.g. --benchmark_filter=chroma
                       --benchmark_repetitions=5 (without --ratios; --benchmark_list_tests=true)
  --help               this text; --version: the version

Exit codes: 0 done, 1 no photograph, no CPU to pin to or an inexact formulation, 2 usage error.
See bench/README.md.
)";

}  // namespace

int main(int argc, char** argv)
{
    // Asked what it is, the tool answers before it pins a CPU or checks anything.
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
            std::fputs(kUsage, stdout);
            return 0;
        }
        if (std::strcmp(argv[i], "--version") == 0) {
            std::printf("mirror-bench %s\n", MIRROR_VERSION);
            return 0;
        }
    }
    bool ratios = false;
    bool chromaRatios = true;
    bool faceRatios = true;
    bool renderRatios = true;
    std::string image;
    std::string overlays = std::string(MIRROR_SOURCE_DIR) + "/assets/overlays/catalogue.toml";
    std::vector<char*> args{argv[0]};
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--ratios") == 0) {
            ratios = true;
        } else if (std::strcmp(argv[i], "--ratios=faces") == 0) {
            ratios = true;
            chromaRatios = false;
            renderRatios = false;
        } else if (std::strcmp(argv[i], "--ratios=chroma") == 0) {
            ratios = true;
            faceRatios = false;
            renderRatios = false;
        } else if (std::strcmp(argv[i], "--ratios=render") == 0) {
            ratios = true;
            chromaRatios = false;
            faceRatios = false;
        } else if (std::strncmp(argv[i], "--image=", 8) == 0) {
            image = argv[i] + 8;
        } else if (std::strncmp(argv[i], "--overlays=", 11) == 0) {
            overlays = argv[i] + 11;
        } else if (std::strncmp(argv[i], "--benchmark_", 12) == 0) {
            args.push_back(argv[i]);
        } else {
            std::fprintf(stderr, "mirror-bench: unknown option '%s' (see --help)\n", argv[i]);
            return 2;
        }
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
            if (chromaRatios) {
                bench::CardTrackerCase card(frame, kCardFrames);
                bench::printRatios(chroma, card);
                std::fflush(stdout);
            }
            if (faceRatios) {
                bench::printFaceRatios(faceCases());
                std::fflush(stdout);
            }
            if (renderRatios)
                bench::printRenderRatios(overlays);
            return 0;
        }

        registerChromaticity(chroma);
        registerCardTracker(frame);
        registerFaces();
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
