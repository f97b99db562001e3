// facegen: multi-face test sequences composed from real photographs, with ground truth, for
// `mirror-eval track`. Heads cut from IMM photographs (by their landmarks) move, roll and scale
// over a real background photograph whose own faces stay still. See README.md.

#include "compositor.hpp"
#include "face_photo.hpp"
#include "sequence_writer.hpp"
#include "shared_data.hpp"
#include "tool_cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <opencv2/core/utility.hpp>
#include <string>

namespace {

int measureSize(const std::string& dataDir, const std::string& cascade)
{
    const std::string imm = (std::filesystem::path(dataDir) / "imm_face_db").string();
    const facegen::SizeMeasurement m =
        facegen::measureBoxAgainstLandmarks(facegen::frontalImmFaces(imm), cascade);
    std::printf(
        "photos=%d detected=%d box_per_width=%.4f (std %.4f) offset_x=%.4f "
        "offset_y=%.4f (widths, face frame)\n",
        m.photos, m.detected, m.boxPerWidth, m.boxPerWidthStd, m.offsetX, m.offsetY);
    std::printf("compiled in: box_per_width=%.4f offset_x=%.4f offset_y=%.4f\n",
                facegen::kBoxPerWidth, facegen::kBoxOffsetX, facegen::kBoxOffsetY);
    return m.detected > 0 ? 0 : 1;
}

int check(const std::string& dir, const std::string& cascade, int step)
{
    const facegen::CheckResult r = facegen::checkSequence(dir, cascade, step);
    const char* bins[3] = {"|roll|<=10", "10<|roll|<=20", "|roll|>20"};
    int all = 0, found = 0;
    for (int b = 0; b < 3; ++b) {
        std::printf("moving %-14s found %4d of %4d (%.0f%%)\n", bins[b], r.movingFound[b],
                    r.moving[b], r.moving[b] ? 100.0 * r.movingFound[b] / r.moving[b] : 0.0);
        all += r.moving[b];
        found += r.movingFound[b];
    }
    std::printf("static faces         found %4d of %4d\n", r.staticFound, r.staticFaces);
    std::printf(
        "check: frames=%d upright_moving_found=%d/%d moving_found=%d/%d static_found=%d/%d "
        "other_hits=%d\n",
        r.frames, r.movingFound[0], r.moving[0], found, all, r.staticFound, r.staticFaces,
        r.otherHits);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"facegen: multi-face sequences with ground truth composed from real photographs"};
    std::string scenario;
    bool list = false;
    bool measure = false;
    std::string checkDir;
    int checkStep = 1;
    std::string out;
    int frames = facegen::kDefaultFrames;
    std::uint32_t seed = 1;
    std::string size = "640x480";
    facegen::GenerateOptions base;
    base.cascadePath = facegen::kDefaultCascade;
    tool_cli::addVersion(app, "facegen");
    std::vector<std::string> known{"all"};
    for (const auto& s : facegen::scenarios())
        known.push_back(s.name);
    app.add_option("--scenario", scenario, "the sequence to render, or 'all' (see --list)")
        ->check(CLI::IsMember(known));
    app.add_flag("--list", list, "list the scenarios and exit");
    app.add_option("--out", out,
                   "output folder (frames/, truth/, README.txt); with --scenario all, OUT/<name>/");
    app.add_option("--frames", frames, "frames per sequence")->check(CLI::Range(2, 100000));
    app.add_option("--seed", seed, "varies faces, paths, light and noise");
    app.add_option("--size", size, "frame size WIDTHxHEIGHT")->capture_default_str();
    base.dataDir = tool_data::defaultDir();
    app.add_option("--data", base.dataDir, "the shared real data folder")->capture_default_str();
    app.add_option("--cascade", base.cascadePath, "OpenCV cascade for static faces and checks")
        ->capture_default_str();
    app.add_option("--background", base.background, "use this photograph as background instead");
    app.add_option("--faces", base.faces,
                   "the moving faces only from IMM photographs whose name starts with one of "
                   "these (07: person 07, 07-1: their type 1 photograph)")
        ->delimiter(',');
    app.add_option("--shake", base.shakePx,
                   "camera shake: the whole view shifted by up to this many pixels and turned "
                   "by 0.15 degrees a pixel, each frame (0: a still camera)")
        ->check(CLI::Range(0.0, 20.0));
    app.add_option("--check", checkDir,
                   "run OpenCV's cascade over a written sequence and count the faces it finds");
    app.add_option("--check-step", checkStep, "with --check: every n-th frame")
        ->check(CLI::Range(1, 1000));
    app.add_flag("--measure-size", measure,
                 "measure the detector's box against the IMM landmark width and exit");
    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;

    cv::setNumThreads(1);  // --measure-size and --check repeatable too
    try {
        if (list) {
            for (const auto& s : facegen::scenarios())
                std::printf("%-12s %s\n", s.name, s.description);
            return 0;
        }
        // The faces are IMM photographs: without the shared data there is nothing to render.
        if (const std::string why = tool_data::missingReason(base.dataDir);
            !why.empty() && (measure || checkDir.empty())) {
            std::fprintf(stderr, "facegen: %s\n", why.c_str());
            return 1;
        }
        if (measure)
            return measureSize(base.dataDir, base.cascadePath);
        if (!checkDir.empty())
            return check(checkDir, base.cascadePath, checkStep);

        int w = 0, h = 0;
        char tail = 0;
        if (std::sscanf(size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 160 || h < 120 ||
            w > 8192 || h > 8192) {
            std::fprintf(stderr,
                         "facegen: --size %s: expected WIDTHxHEIGHT, 160x120 to 8192x8192\n",
                         size.c_str());
            return 2;
        }
        if (out.empty() || scenario.empty()) {
            std::fprintf(stderr,
                         "facegen: give --out DIR and --scenario NAME|all (--list shows them)\n");
            return 2;
        }
        base.frames = frames;
        base.seed = seed;
        base.size = cv::Size(w, h);
        std::vector<std::string> names;
        if (scenario == "all")
            for (const auto& s : facegen::scenarios())
                names.push_back(s.name);
        else
            names.push_back(scenario);
        for (const std::string& name : names) {
            facegen::GenerateOptions o = base;
            o.scenario = name;
            o.outDir = scenario == "all" ? (std::filesystem::path(out) / name).string() : out;
            const facegen::GeneratedSequence seq = facegen::generateSequence(o);
            std::printf(
                "%s: %d frames %dx%d, %d moving + %d static faces, into %s (background %s)\n",
                name.c_str(), seq.frames, w, h, seq.movingFaces, seq.staticFaces, seq.dir.c_str(),
                seq.background.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "facegen: %s\n", e.what());
        return 1;
    }
    return 0;
}
