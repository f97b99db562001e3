// cardgen: renders colour-card sequences with ground truth over real photographs, for evaluating
// the card tracker (mirror-eval card). See scenarios.cpp for what each sequence does.

#include "sequence_writer.hpp"
#include "shared_data.hpp"
#include "tool_cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

int main(int argc, char** argv)
{
    CLI::App app{"cardgen: colour-card sequences with ground truth over real photographs"};
    std::string scenario;
    bool all = false;
    bool list = false;
    std::string out;
    int frames = cardgen::kDefaultFrames;
    std::uint32_t seed = 1;
    std::string size = "720x480";
    cardgen::GenerateOptions base;
    tool_cli::addVersion(app, "cardgen");
    std::vector<std::string> names;
    for (const auto& s : cardgen::scenarios())
        names.push_back(s.name);
    app.add_option("--scenario", scenario, "the sequence to render (see --list)")
        ->check(CLI::IsMember(names));
    app.add_flag("--all", all, "render every scenario into OUT/<name>/");
    app.add_flag("--list", list, "list the scenarios and exit");
    app.add_option("--out", out, "output folder (frame_00000.png..., truth.csv, scenario.txt)");
    app.add_option("--frames", frames, "frames per sequence, frame 0 included")
        ->check(CLI::Range(2, 100000));
    app.add_option("--seed", seed, "varies the motion phases and the noise");
    app.add_option("--size", size, "frame size WIDTHxHEIGHT")->capture_default_str();
    base.dataDir = tool_data::defaultDir();
    app.add_option("--data", base.dataDir, "the shared real data folder (backgrounds)")
        ->capture_default_str();
    app.add_option("--background", base.background, "use this photograph as background instead");
    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;

    if (list) {
        for (const auto& s : cardgen::scenarios())
            std::printf("%-15s %s\n", s.name, s.description);
        return 0;
    }
    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 64 || h < 48 || w > 8192 ||
        h > 8192) {
        std::fprintf(stderr, "cardgen: --size %s: expected WIDTHxHEIGHT, 64x48 to 8192x8192\n",
                     size.c_str());
        return 2;
    }
    if (out.empty() || (all == !scenario.empty())) {
        std::fprintf(stderr,
                     "cardgen: give --out DIR and either --scenario NAME or --all "
                     "(--list shows the scenarios)\n");
        return 2;
    }
    // Without the shared photographs the same seed renders other backgrounds: say so.
    if (const std::string why = tool_data::missingReason(base.dataDir);
        !why.empty() && base.background.empty())
        std::fprintf(stderr, "cardgen: %s: backgrounds from Debian's opencv-doc images only\n",
                     why.c_str());
    base.frames = frames;
    base.seed = seed;
    base.size = cv::Size(w, h);
    try {
        if (!all)
            names = {scenario};
        for (const std::string& name : names) {
            cardgen::GenerateOptions o = base;
            o.scenario = name;
            o.outDir = all ? (std::filesystem::path(out) / name).string() : out;
            const cardgen::GeneratedSequence seq = cardgen::generateSequence(o);
            std::printf("%s: %d frames %dx%d into %s (background %s)\n", name.c_str(), seq.frames,
                        w, h, seq.dir.c_str(), seq.background.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cardgen: %s\n", e.what());
        return 1;
    }
    return 0;
}
