#include "sequence_writer.hpp"

#include "compositor.hpp"
#include "face_photo.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace facegen {

namespace {

std::string numbered(int index, const char* extension)
{
    char name[32];
    std::snprintf(name, sizeof name, "%06d.%s", index, extension);
    return name;
}

void makeFreshFolder(const fs::path& dir, const char* extension)
{
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw std::runtime_error("output " + dir.string() + ": cannot create folder (" +
                                 ec.message() + ")");
    // Stale files of a longer earlier run would make frames and truth disagree.
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == extension)
            fs::remove(entry.path(), ec);
}

}  // namespace

std::string truthLine(const FaceState& f)
{
    // No "-0.00": a roll that rounds to zero is written as 0.00.
    const double roll = std::abs(f.rollDeg) < 0.005 ? 0.0 : f.rollDeg;
    char line[128];
    std::snprintf(line, sizeof line, "%d %.2f %.2f %.2f %.2f %d", f.id, f.cx, f.cy, f.size, roll,
                  f.moving ? 1 : 0);
    return line;
}

struct SequenceRenderer::Impl {
    /// The photographs of `all` whose file name starts with one of `prefixes` (all when none).
    static std::vector<std::string> chosenFaces(std::vector<std::string> all,
                                                const std::vector<std::string>& prefixes)
    {
        if (prefixes.empty())
            return all;
        std::vector<std::string> kept;
        for (const std::string& prefix : prefixes) {
            const std::size_t before = kept.size();
            for (const std::string& path : all)
                if (fs::path(path).filename().string().rfind(prefix, 0) == 0 &&
                    std::find(kept.begin(), kept.end(), path) == kept.end())
                    kept.push_back(path);
            if (kept.size() == before)
                throw std::runtime_error("--faces " + prefix +
                                         ": no frontal IMM photograph's name starts with it");
        }
        return kept;
    }

    static std::string backgroundOf(const GenerateOptions& o)
    {
        const ScenarioInfo* info = findScenario(o.scenario);
        if (info == nullptr)
            (void)Scenario(o.scenario, o.size, o.frames, o.seed, {}, {});  // throws the names
        return o.background.empty() ? (fs::path(o.dataDir) / info->background).string()
                                    : o.background;
    }

    explicit Impl(const GenerateOptions& o)
        : options(o),
          bgPath(backgroundOf(o)),
          background(loadBackground(bgPath, o.size,
                                    o.cascadePath.empty() ? kDefaultCascade : o.cascadePath)),
          sources(chosenFaces(frontalImmFaces((fs::path(o.dataDir) / "imm_face_db").string()),
                              o.faces)),
          scenario(o.scenario, o.size, o.frames, o.seed, sources, background.faces)
    {
        for (const FacePath& p : scenario.paths())
            sprites.emplace_back(loadImmFace(sources[p.source]));
    }

    GenerateOptions options;
    std::string bgPath;
    Background background;
    std::vector<std::string> sources;
    Scenario scenario;
    std::vector<FaceSprite> sprites;
};

SequenceRenderer::SequenceRenderer(const GenerateOptions& options)
    : impl_(std::make_unique<Impl>(options))
{
}

SequenceRenderer::~SequenceRenderer() = default;

SequenceRenderer::Frame SequenceRenderer::frame(int i) const
{
    const GenerateOptions& o = impl_->options;
    const std::vector<FaceState> scene = impl_->scenario.frame(i);
    const double u = o.frames > 1 ? static_cast<double>(i) / (o.frames - 1) : 0.0;
    const CameraShake shake = shakeAt(o.seed, i, o.shakePx);
    Frame f;
    f.bgr = renderFrame(impl_->background, impl_->sprites, scene, lightingAt(o.seed, u),
                        static_cast<std::uint64_t>(o.seed) * 100003u + i, shake);
    for (const FaceState& s : scene)
        f.faces.push_back(shaken(s, shake, o.size));
    return f;
}

const std::string& SequenceRenderer::backgroundPath() const noexcept
{
    return impl_->bgPath;
}
const Scenario& SequenceRenderer::scenario() const noexcept
{
    return impl_->scenario;
}
const std::vector<FaceState>& SequenceRenderer::staticFaces() const noexcept
{
    return impl_->background.faces;
}
const std::vector<std::string>& SequenceRenderer::staticOrigins() const noexcept
{
    return impl_->background.origins;
}
const std::vector<std::string>& SequenceRenderer::faceSources() const noexcept
{
    return impl_->sources;
}

GeneratedSequence generateSequence(const GenerateOptions& o)
{
    // One thread: the cascade's static faces, and so the truth, must not depend on scheduling.
    cv::setNumThreads(1);
    const SequenceRenderer renderer(o);
    const ScenarioInfo* info = findScenario(o.scenario);
    const std::string& bgPath = renderer.backgroundPath();
    const Scenario& scenario = renderer.scenario();
    const std::vector<std::string>& sources = renderer.faceSources();
    const std::vector<FaceState>& staticFaces = renderer.staticFaces();

    const fs::path framesDir = fs::path(o.outDir) / "frames";
    const fs::path truthDir = fs::path(o.outDir) / "truth";
    makeFreshFolder(framesDir, ".png");
    makeFreshFolder(truthDir, ".txt");

    GeneratedSequence result;
    result.dir = o.outDir;
    result.background = bgPath;
    result.movingFaces = static_cast<int>(scenario.paths().size());
    result.staticFaces = static_cast<int>(staticFaces.size());
    const std::vector<int> pngParams = {cv::IMWRITE_PNG_COMPRESSION, 1};
    for (int i = 0; i < o.frames; ++i) {
        const SequenceRenderer::Frame rendered = renderer.frame(i);
        const cv::Mat& frame = rendered.bgr;
        const std::vector<FaceState>& faces = rendered.faces;
        const std::string png = (framesDir / numbered(i, "png")).string();
        if (!cv::imwrite(png, frame, pngParams))
            throw std::runtime_error("output " + png + ": cannot write PNG");
        const std::string txt = (truthDir / numbered(i, "txt")).string();
        std::ofstream truth(txt);
        bool anyMoving = false;
        for (const FaceState& f : faces) {
            truth << truthLine(f) << '\n';
            anyMoving = anyMoving || f.moving;
        }
        if (!truth)
            throw std::runtime_error("output " + txt + ": cannot write");
        result.framesWithoutMovingFace += anyMoving ? 0 : 1;
    }
    result.frames = o.frames;

    std::ofstream text(fs::path(o.outDir) / "README.txt");
    text << "facegen sequence\n"
         << "scenario: " << info->name << "\n"
         << "description: " << info->description << "\n"
         << "frames: " << o.frames << " (30 per second of scene time)\n"
         << "size: " << o.size.width << "x" << o.size.height << "\n"
         << "seed: " << o.seed << "\n"
         << "background: " << bgPath << " (scaled to cover the frame, centre-cropped)\n"
         << "static faces: " << staticFaces.size() << " (found on the background by "
         << (o.cascadePath.empty() ? kDefaultCascade : o.cascadePath)
         << ", scale 1.1, 5 neighbours, plus annotated ones it misses; ids 101...)\n";
    for (std::size_t i = 0; i < staticFaces.size(); ++i)
        text << "  " << truthLine(staticFaces[i]) << "  (" << renderer.staticOrigins()[i] << ")\n";
    for (std::size_t i = 0; i < scenario.paths().size(); ++i) {
        const FacePath& p = scenario.paths()[i];
        char line[200];
        std::snprintf(line, sizeof line,
                      "moving face %zu: %s, frames %d-%d, box %.0f px +-%.0f%%, roll amplitude "
                      "%.1f deg\n",
                      i + 1, sources[p.source].c_str(),
                      static_cast<int>(std::ceil(p.u0 * (o.frames - 1))),
                      static_cast<int>(std::floor(p.u1 * (o.frames - 1))), p.size, 100 * p.sizeAmp,
                      p.rollAmp);
        text << line;
    }
    text << "frames without a moving face in view: " << result.framesWithoutMovingFace << "\n"
         << "lighting: global gain 1 +- 0.06 and a left-right gradient +- 0.05, drifting; sensor "
            "noise Gaussian sigma "
         << kNoiseSigma << " grey levels per channel\n"
         << "camera shake: " << o.shakePx << " px amplitude, +-" << kShakeRollPerPixel * o.shakePx
         << " degrees (the whole view; truth in the shaken frame)\n"
         << "\n"
         << "frames/NNNNNN.png: BGR PNG. truth/NNNNNN.txt: one line per face in that frame:\n"
         << "  id cx cy size roll_deg moving\n"
         << "- id: moving faces 1..4 (stable over the sequence), static faces 101...;\n"
         << "- cx cy: centre of the face box, pixels, pixel centres at integer coordinates;\n"
         << "- size: side of the square face box, in the convention of OpenCV's\n"
         << "  haarcascade_frontalface_default: for an upright face it equals that detector's box\n"
         << "  on average (measured on the IMM photographs: box = " << kBoxPerWidth
         << " x the jaw-to-jaw landmark width,\n"
         << "  centre offset (" << kBoxOffsetX << ", " << kBoxOffsetY
         << ") widths from the eye-mouth midpoint); rolled faces: the same box turned\n"
         << "  with the face about its centre (the line gives the unrotated side);\n"
         << "- roll_deg: clockwise on screen (y down) positive; the face's midline (eye midpoint,\n"
         << "  nose, mouth centre) against vertical; static faces 0 (upright by assumption);\n"
         << "- moving: 1 for the composed moving faces, 0 for the background's static faces\n"
         << "  (real faces that do not move and should not be tracked).\n"
         << "A moving face is listed whenever its box touches the frame (faces entering and\n"
         << "leaving are listed while partly out of view: an evaluator may ignore faces whose box\n"
         << "is not wholly inside). No two faces overlap by more than "
         << static_cast<int>(kMaxOverlap * 100) << "% of the smaller box.\n";
    if (!text)
        throw std::runtime_error("output " + o.outDir + "/README.txt: cannot write");
    return result;
}

CheckResult checkSequence(const std::string& dir, const std::string& cascadePath, int step)
{
    cv::CascadeClassifier cascade;
    if (!cascade.load(cascadePath))
        throw std::runtime_error("cascade " + cascadePath + ": cannot load");
    CheckResult r;
    for (int i = 0;; i += std::max(1, step)) {
        const fs::path png = fs::path(dir) / "frames" / numbered(i, "png");
        const fs::path txt = fs::path(dir) / "truth" / numbered(i, "txt");
        std::error_code ec;
        if (!fs::is_regular_file(png, ec))
            break;
        const cv::Mat grey = cv::imread(png.string(), cv::IMREAD_GRAYSCALE);
        std::ifstream in(txt);
        if (grey.empty() || !in)
            throw std::runtime_error("sequence " + dir + ": cannot read frame or truth " +
                                     std::to_string(i));
        std::vector<FaceState> truth;
        std::string line;
        while (std::getline(in, line)) {
            std::istringstream s(line);
            FaceState f;
            int moving = 0;
            if (!(s >> f.id >> f.cx >> f.cy >> f.size >> f.rollDeg >> moving))
                throw std::runtime_error("sequence " + txt.string() + ": bad line '" + line + "'");
            f.moving = moving != 0;
            truth.push_back(f);
        }
        std::vector<cv::Rect> hits;
        cascade.detectMultiScale(grey, hits, 1.1, 3, 0, cv::Size(24, 24));
        std::vector<bool> used(hits.size(), false);
        for (const FaceState& f : truth) {
            const double h = f.size / 2;
            const bool inside = f.cx - h >= 0 && f.cy - h >= 0 && f.cx + h <= grey.cols - 1 &&
                                f.cy + h <= grey.rows - 1;
            bool found = false;
            for (std::size_t k = 0; k < hits.size(); ++k) {
                const cv::Rect& b = hits[k];
                const double dx = b.x + b.width * 0.5 - 0.5 - f.cx;
                const double dy = b.y + b.height * 0.5 - 0.5 - f.cy;
                const double ratio = b.width / f.size;
                if (std::hypot(dx, dy) <= 0.3 * f.size && ratio >= 1 / 1.5 && ratio <= 1.5) {
                    found = true;
                    used[k] = true;
                }
            }
            if (!f.moving) {
                ++r.staticFaces;
                r.staticFound += found ? 1 : 0;
            } else if (inside) {
                const double roll = std::abs(f.rollDeg);
                const int bin = roll <= 10 ? 0 : roll <= 20 ? 1 : 2;
                ++r.moving[bin];
                r.movingFound[bin] += found ? 1 : 0;
            }
        }
        for (const bool u : used)
            r.otherHits += u ? 0 : 1;
        ++r.frames;
    }
    if (r.frames == 0)
        throw std::runtime_error("sequence " + dir + ": no frames/000000.png");
    return r;
}

}  // namespace facegen
