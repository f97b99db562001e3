#include "sequence_writer.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace cardgen {

namespace {

std::string colourOf(const platform::CardPaint& p)
{
    char text[32];
    std::snprintf(text, sizeof text, "#%02x%02x%02x", p.red, p.green, p.blue);
    return text;
}

}  // namespace

std::string resolveBackground(const ScenarioInfo& info, const std::string& dataDir,
                              const std::string& override)
{
    return resolveBackground(info.name, info.backgrounds, dataDir, override);
}

std::string resolveBackground(const std::string& scenario,
                              const std::vector<std::string>& candidates,
                              const std::string& dataDir, const std::string& override)
{
    if (!override.empty()) {
        if (cv::imread(override, cv::IMREAD_REDUCED_COLOR_8).empty())
            throw std::runtime_error("background " + override + ": cannot read");
        return override;
    }
    std::string tried;
    for (const std::string& candidate : candidates) {
        const std::string path = fs::path(candidate).is_absolute()
                                     ? candidate
                                     : (fs::path(dataDir) / candidate).string();
        std::error_code ec;
        if (fs::is_regular_file(path, ec) && !cv::imread(path, cv::IMREAD_REDUCED_COLOR_8).empty())
            return path;
        tried += (tried.empty() ? "" : ", ") + path;
    }
    throw std::runtime_error("scenario " + scenario +
                             ": no readable background photograph (tried " + tried +
                             "; set --data to the shared data folder or give --background)");
}

std::string truthRow(int frame, const FrameSpec& spec)
{
    char row[200];
    if (!spec.card) {
        std::snprintf(row, sizeof row, "%d,,,,,,,,", frame);
        return row;
    }
    const vision::Quad q = truthCorners(spec.quad);
    std::snprintf(row, sizeof row, "%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f", frame, q[0].x,
                  q[0].y, q[1].x, q[1].y, q[2].x, q[2].y, q[3].x, q[3].y);
    return row;
}

GeneratedSequence generateSequence(const GenerateOptions& o)
{
    const Scenario scenario(o.scenario, o.size, o.frames, o.seed);
    GeneratedSequence result;
    result.dir = o.outDir;
    result.background =
        resolveBackground(o.scenario, scenario.backgrounds(), o.dataDir, o.background);
    const cv::Mat background = loadBackground(result.background, o.size);

    std::error_code ec;
    fs::create_directories(o.outDir, ec);
    if (ec || !fs::is_directory(o.outDir))
        throw std::runtime_error("output " + o.outDir + ": cannot create folder (" + ec.message() +
                                 ")");
    // Stale frames of a longer earlier run would make the folder disagree with truth.csv.
    for (const auto& entry : fs::directory_iterator(o.outDir)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("frame_", 0) == 0 && entry.path().extension() == ".png")
            fs::remove(entry.path(), ec);
    }

    const std::string truthPath = (fs::path(o.outDir) / "truth.csv").string();
    std::ofstream truth(truthPath);
    if (!truth)
        throw std::runtime_error("output " + truthPath + ": cannot write");
    truth << "frame,x0,y0,x1,y1,x2,y2,x3,y3\n";

    const std::vector<int> pngParams = {cv::IMWRITE_PNG_COMPRESSION, 1};
    for (int i = 0; i < o.frames; ++i) {
        const FrameSpec spec = scenario.frame(i);
        const cv::Mat frame =
            renderFrame(background, spec, static_cast<std::uint64_t>(o.seed) * 100003u + i);
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", i);
        const std::string path = (fs::path(o.outDir) / name).string();
        if (!cv::imwrite(path, frame, pngParams))
            throw std::runtime_error("output " + path + ": cannot write PNG");
        truth << truthRow(i, spec) << '\n';
        result.framesWithoutCard += spec.card ? 0 : 1;
    }
    truth.close();
    if (!truth)
        throw std::runtime_error("output " + truthPath + ": write failed");
    result.frames = o.frames;

    const FrameSpec first = scenario.frame(std::min(1, o.frames - 1));
    std::ofstream text(fs::path(o.outDir) / "scenario.txt");
    text << "scenario: " << scenario.info().name << "\n"
         << "description: " << scenario.info().description << "\n"
         << "frames: " << o.frames << " (30 per second of scene time)\n"
         << "size: " << o.size.width << "x" << o.size.height << "\n"
         << "seed: " << o.seed << "\n"
         << "background: " << result.background << "\n"
         << "card colour: " << colourOf(first.paint) << " (RGB, before shading and gain)\n";
    if (!scenario.choices().empty())
        text << "the seed's choices: " << scenario.choices() << "\n";
    text << "frames without a card in view: " << result.framesWithoutCard << "\n"
         << "\n"
         << "Frame 0 is the training frame: the card fills the whole view (its corners lie just\n"
         << "outside the image). Train the colour model on all of frame 0.\n"
         << "\n"
         << "truth.csv: one header line, then one row per frame: frame,x0,y0,x1,y1,x2,y2,x3,y3\n"
         << "- corners of the card clockwise on screen from its top-left corner (top-left,\n"
         << "  top-right, bottom-right, bottom-left), in pixels, with pixel centres at integer\n"
         << "  coordinates (pixel (0,0) covers -0.5..0.5);\n"
         << "- corners may lie outside the image (a corner or more out of view): they are the\n"
         << "  true positions, not clipped; parts hidden by an occluder are included too;\n"
         << "- a frame with no card in view at all has empty corner fields: e.g. \"17,,,,,,,,\".\n"
         << "\n"
         << "Evaluate with: mirror-eval card --video " << o.outDir << " --truth " << truthPath
         << "\n";
    if (!text)
        throw std::runtime_error("output " + o.outDir + "/scenario.txt: cannot write");
    return result;
}

}  // namespace cardgen
