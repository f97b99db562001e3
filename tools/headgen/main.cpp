// headgen: synthetic heads with known pose for the AAM fit's evaluation (§5): a textured CANDIDE-3
// head at known yaw, pitch, roll, scale, translation and expression over real backgrounds, with
// or without a hand in front; frames and a truth file each. See README.md.

#include "head_scene.hpp"
#include "shared_data.hpp"
#include "tool_cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <opencv2/core/utility.hpp>
#include <string>

namespace {

/// A bad argument: one line on stderr, exit code 2.
int usageError(const std::string& what)
{
    std::fprintf(stderr, "headgen: %s\n", what.c_str());
    return 2;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"headgen: textured CANDIDE heads at known poses over real backgrounds"};
    tool_cli::addVersion(app, "headgen");
    headgen::SceneOptions o;
    std::string out, size = "640x480", hand = "none", kind = "sequence";
    app.add_option("--out", out, "output folder (frames/, truth/, README.txt)");
    app.add_option("--kind", kind, "sequence (smooth motion) or single (independent frames)")
        ->capture_default_str();
    app.add_option("--frames", o.motion.frames, "frames to write")->capture_default_str();
    app.add_option("--seed", o.motion.seed, "the same seed, the same frames")
        ->capture_default_str();
    app.add_option("--size", size, "frame size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--hand", hand, "a hand in front: none, some or all frames")
        ->capture_default_str();
    app.add_option("--max-yaw", o.motion.maxYawDeg, "|yaw| at most, degrees")
        ->capture_default_str();
    app.add_option("--max-pitch", o.motion.maxPitchDeg, "|pitch| at most, degrees")
        ->capture_default_str();
    app.add_option("--max-roll", o.motion.maxRollDeg, "|roll| at most, degrees")
        ->capture_default_str();
    app.add_option("--faces", o.faces,
                   "IMM .asf files texturing the heads (default: the persons the demo model "
                   "leaves out, 04, 08, ... 40)");
    o.dataDir = tool_data::defaultDir();
    app.add_option("--data", o.dataDir, "the shared real data folder")->capture_default_str();
    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;

    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 160 || h < 120 ||
        w > 4096 || h > 4096)
        return usageError("--size " + size + ": expected WIDTHxHEIGHT, 160x120 to 4096x4096");
    if (out.empty())
        return usageError("give --out DIR");
    if (kind != "sequence" && kind != "single")
        return usageError("--kind " + kind + ": expected sequence or single");
    if (o.motion.frames < 1 || o.motion.frames > 100000)
        return usageError("--frames must be in 1..100000");
    for (const double limit : {o.motion.maxYawDeg, o.motion.maxPitchDeg, o.motion.maxRollDeg})
        if (!(limit >= 0 && limit <= 60))
            return usageError("--max-yaw, --max-pitch and --max-roll must be in 0..60 degrees");
    try {
        o.motion.hand = headgen::handModeNamed(hand);
    } catch (const std::exception& e) {
        return usageError(e.what());
    }
    o.motion.sequence = kind == "sequence";
    o.motion.size = cv::Size(w, h);

    cv::setNumThreads(1);  // the backgrounds' cascade faces cannot depend on scheduling
    try {
        const headgen::HeadScene scene(o);
        headgen::writeScene(scene, o, out);
        std::printf("headgen: %d %s frames %dx%d, %zu textures, into %s\n", scene.frames(),
                    kind.c_str(), w, h, scene.textures().size(), out.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "headgen: %s\n", e.what());
        return 1;
    }
    return 0;
}
