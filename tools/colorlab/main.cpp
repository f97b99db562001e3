// colorlab: the illumination experiment of ch. 3 as a field tool (tools/colorlab/README.md).
//
//   colorlab INPUT (--samples FILE | --grid NxM) --out DIR [--radius R] [--exclude-saturated]
//   colorlab generate --out DIR [--frames N]
//
// Exit codes: 0 done; 1 the input or an output cannot be read or written; 2 usage or a problem
// with the samples (unreadable or malformed list, no samples, a sample outside the frame).

#include "experiment.hpp"
#include "ramp_generator.hpp"
#include "tool_cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInput = 1;
constexpr int kExitUsage = 2;

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{
        "colorlab: how colour spaces react to a change of light (method ch. 3). Samples points of "
        "a video or frame folder, converts them to every colour space, writes per-sample series, "
        "the standard deviation and discriminative-power tables, plots and a ranking.",
        "colorlab"};
    app.footer(
        "Sample list: one `name x y [radius]` a line, '#' comments.\n"
        "Exit codes: 0 ok, 1 input/output error, 2 usage or sample problem.");

    colorlab::AnalysisOptions analysis;
    app.add_option("input", analysis.input, "video file, folder of frames, or a quoted glob");
    app.add_option("--samples", analysis.samplesFile, "sample list file");
    app.add_option("--grid", analysis.grid, "automatic grid of NxM samples instead of a list");
    app.add_option("--radius", analysis.radius, "radius of the sampled disc for --grid (default 3)")
        ->check(CLI::Range(0, 100));
    app.add_option("-o,--out", analysis.outDir, "output folder");
    app.add_flag("--exclude-saturated", analysis.excludeSaturated,
                 "leave out frames where a sampled pixel has a channel at 255");
    app.add_option("--max-frames", analysis.maxFrames, "stop after N frames (0 = all)")
        ->check(CLI::NonNegativeNumber);
    bool noPlots = false;
    app.add_flag("--no-plots", noPlots, "skip the PNG plots");

    colorlab::RampOptions ramp;
    CLI::App* generate = app.add_subcommand(
        "generate", "write a recording of coloured patches under a light ramp (known answer)");
    generate->add_option("-o,--out", ramp.outDir, "output folder for the frames")->required();
    generate->add_option("--frames", ramp.frames, "number of frames (default 60)")
        ->check(CLI::Range(2, 100000));
    generate->add_option("--seed", ramp.seed, "noise seed");

    tool_cli::addVersion(app, "colorlab");
    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;

    try {
        if (generate->parsed()) {
            colorlab::generateRamp(ramp);
            std::printf("colorlab: wrote %d frames, samples.txt and illumination.csv to %s\n",
                        ramp.frames, ramp.outDir.c_str());
            return kExitOk;
        }
        if (analysis.input.empty() || analysis.outDir.empty()) {
            std::fprintf(stderr,
                         "colorlab: need INPUT and --out DIR (and --samples FILE or --grid NxM); "
                         "see --help\n");
            return kExitUsage;
        }
        if (!analysis.samplesFile.empty() && !analysis.grid.empty()) {
            std::fprintf(stderr, "colorlab: give either --samples or --grid, not both\n");
            return kExitUsage;
        }
        analysis.plots = !noPlots;
        const colorlab::AnalysisResult result = colorlab::runAnalysis(analysis);
        std::printf(
            "colorlab: %zu samples, %s; tables and plots in %s\n\n%s",
            result.recording.samples.size(),
            (std::to_string(result.frames.used()) + " of " + std::to_string(result.frames.total) +
             " frames used, " + std::to_string(result.frames.saturated) + " saturated" +
             (result.frames.excluded ? " (excluded)" : ""))
                .c_str(),
            analysis.outDir.c_str(), result.rankingText.c_str());
        return kExitOk;
    } catch (const colorlab::SampleError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return kExitUsage;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "colorlab: %s\n", e.what());
        return kExitInput;
    }
}
