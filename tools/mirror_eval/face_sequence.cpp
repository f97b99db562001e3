#include "face_sequence.hpp"

#include "face_truth.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace mirror_eval {

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> listFrames(const std::string& dir, int start, int maxFrames)
{
    if (!fs::is_directory(dir))
        throw std::runtime_error("frames " + dir + ": not a folder");
    std::vector<fs::path> frames;
    for (const auto& e : fs::directory_iterator(dir)) {
        std::string ext = e.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (e.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".jpeg"))
            frames.push_back(e.path());
    }
    std::sort(frames.begin(), frames.end());
    if (frames.empty())
        throw std::runtime_error("frames " + dir + ": no PNG/JPEG frames");
    if (start >= static_cast<int>(frames.size()))
        throw std::runtime_error("--start " + std::to_string(start) + ": the sequence has only " +
                                 std::to_string(frames.size()) + " frames");
    frames.erase(frames.begin(), frames.begin() + start);
    if (maxFrames > 0 && static_cast<int>(frames.size()) > maxFrames)
        frames.resize(static_cast<std::size_t>(maxFrames));
    return frames;
}

std::vector<TruthFace> composedTruth(const fs::path& file)
{
    std::vector<TruthFace> faces;
    for (const ComposedFace& c : loadComposedTruth(file.string())) {
        TruthFace tf;
        tf.id = c.id;
        tf.box = squareAbout(c.centre, c.size);
        tf.centre = c.centre;
        tf.rollDegrees = c.rollDegrees;
        tf.moving = c.moving;
        faces.push_back(tf);
    }
    return faces;
}

std::vector<TruthFace> landmarkTruth(const fs::path& file)
{
    const std::vector<vision::Point2f> points = loadPts(file.string());
    if (points.size() != 68)
        throw std::runtime_error(file.string() + ": expected 68 points, got " +
                                 std::to_string(points.size()));
    const auto axis = axisPoints68(points);
    TruthFace tf;
    tf.box = boundingBox(points);  // the landmarks' bounding box (face_match.hpp)
    tf.centre = {tf.box.x + 0.5f * tf.box.width, tf.box.y + 0.5f * tf.box.height};
    tf.rollDegrees = axisRollDegrees(axis[0], axis[1], axis[2]);
    tf.eyeRollDegrees = std::atan2(points[36].y - points[31].y, points[36].x - points[31].x) *
                        180.0 / 3.14159265358979323846;
    return {tf};
}

}  // namespace

FaceSequence loadFaceSequence(const std::string& framesDir, const std::string& truthDir, int start,
                              int maxFrames)
{
    const std::vector<fs::path> frames = listFrames(framesDir, start, maxFrames);
    if (!fs::is_directory(truthDir))
        throw std::runtime_error("truth " + truthDir + ": not a folder");
    const std::string first = frames.front().stem().string();
    const bool pts = fs::exists(fs::path(truthDir) / (first + ".pts"));
    const bool txt = fs::exists(fs::path(truthDir) / (first + ".txt"));
    if (!pts && !txt)
        throw std::runtime_error("truth " + truthDir + ": no " + first + ".pts or " + first +
                                 ".txt for frame " + frames.front().filename().string());
    FaceSequence s;
    s.composed = txt && !pts;
    for (const fs::path& f : frames) {
        const fs::path t =
            fs::path(truthDir) / (f.stem().string() + (s.composed ? ".txt" : ".pts"));
        if (!fs::exists(t))
            throw std::runtime_error("truth " + t.string() + ": missing for frame " +
                                     f.filename().string());
        s.frames.push_back(f.string());
        s.truth.push_back(s.composed ? composedTruth(t) : landmarkTruth(t));
    }
    return s;
}

}  // namespace mirror_eval
