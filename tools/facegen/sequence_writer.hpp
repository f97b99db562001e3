#pragma once
// Writes one facegen sequence to a folder: frames/000000.png ..., truth/000000.txt ... and
// README.txt; and checks a written sequence against OpenCV's cascade.

#include "scenarios.hpp"

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace facegen {

struct GenerateOptions {
    std::string scenario;
    std::string outDir;  ///< created if missing; old frames/*.png and truth/*.txt are removed
    int frames = kDefaultFrames;
    std::uint32_t seed = 1;
    cv::Size size{640, 480};
    std::string dataDir = "../shared/data";  ///< the shared real data (relative to the cwd)
    std::string cascadePath;                 ///< empty: Debian's haarcascade_frontalface_default
    std::string background;                  ///< overrides the scenario's photograph when set
    double shakePx = 0;  ///< camera shake amplitude (camera_shake.hpp); 0: a still camera
    /// The moving faces only from IMM photographs whose file name starts with one of these
    /// ("07": person 07's frontal photographs, "07-1": their type 1); empty: any person.
    std::vector<std::string> faces;
};

struct GeneratedSequence {
    std::string dir;
    std::string background;
    int frames = 0;
    int movingFaces = 0;
    int staticFaces = 0;
    int framesWithoutMovingFace = 0;
};

/// Any frame of a sequence, rendered in memory as generateSequence() writes it (the scenario's
/// timeline is that of `options.frames`; a test renders only the frames it needs).
class SequenceRenderer {
public:
    /// Loads the background (its static faces found by the cascade) and the heads. Throws
    /// std::runtime_error as generateSequence() does.
    explicit SequenceRenderer(const GenerateOptions& options);
    ~SequenceRenderer();

    struct Frame {
        cv::Mat bgr;                   ///< 8-bit BGR
        std::vector<FaceState> faces;  ///< the truth, in the frame's (shaken) coordinates
    };
    Frame frame(int index) const;

    const std::string& backgroundPath() const noexcept;
    const Scenario& scenario() const noexcept;
    /// The background's static faces (scene coordinates).
    const std::vector<FaceState>& staticFaces() const noexcept;
    const std::vector<std::string>& staticOrigins() const noexcept;
    const std::vector<std::string>& faceSources() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// One truth line: "id cx cy size roll_deg moving" (2 decimals).
std::string truthLine(const FaceState& face);

/// Renders and writes the whole sequence (sets OpenCV to one thread so the cascade's static faces
/// cannot depend on scheduling). Throws std::runtime_error with one line on failure.
GeneratedSequence generateSequence(const GenerateOptions& options);

/// What OpenCV's cascade finds on a written sequence (--check).
struct CheckResult {
    int frames = 0;
    /// Moving faces whose box is wholly in view, by |roll|: <= 10, 10-20, > 20 degrees.
    int moving[3] = {0, 0, 0};
    int movingFound[3] = {0, 0, 0};
    int staticFaces = 0, staticFound = 0;
    int otherHits = 0;  ///< detections matching no truth face
};

/// Runs cv::CascadeClassifier (1.1, 3 neighbours, min 24 px) on every `step`-th frame of `dir`. A
/// hit matches a face when its centre is within 0.3 x the face's size and the sizes are within a
/// factor 1.5. Throws std::runtime_error when the folder is not a facegen sequence.
CheckResult checkSequence(const std::string& dir, const std::string& cascadePath, int step);

}  // namespace facegen
