#pragma once
// headgen's frames: a textured CANDIDE head (head_renderer.hpp) at the planned pose over a real
// background photograph (the ones facegen composes over), a hand in front when planned, sensor
// noise; and the truth of each frame. Deterministic from the options.

#include "head_motion.hpp"
#include "head_texture.hpp"
#include "head_truth.hpp"
#include "vision/candide_mesh.hpp"

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace headgen {

struct SceneOptions {
    MotionOptions motion;
    std::string dataDir = "../shared/data";
    /// IMM .asf files whose photographs texture the heads; empty: heldOutImmFaces().
    std::vector<std::string> faces;
    std::string cascade;  ///< for the backgrounds' own faces (facegen); empty: Debian's default
};

inline constexpr double kNoiseSigma = 2.0;  ///< grey levels, Gaussian, per channel (as facegen)

class HeadScene {
public:
    /// Reads CANDIDE-3, fits the texture photographs, loads the backgrounds. Throws
    /// std::runtime_error with one line when any of them cannot be read.
    explicit HeadScene(const SceneOptions& options);

    struct Frame {
        cv::Mat bgr;  ///< 8-bit
        HeadTruth truth;
    };
    Frame frame(int index) const;
    int frames() const noexcept { return static_cast<int>(plans_.size()); }
    const vision::CandideMesh& mesh() const noexcept { return mesh_; }
    const std::vector<HeadTexture>& textures() const noexcept { return textures_; }
    const std::vector<std::string>& backgroundPaths() const noexcept { return backgroundPaths_; }

private:
    SceneOptions options_;
    vision::CandideMesh mesh_;
    std::vector<HeadTexture> textures_;
    std::vector<cv::Mat> backgrounds_;  ///< CV_32FC3, the frame's size
    std::vector<std::string> backgroundPaths_;
    std::vector<FramePlan> plans_;
};

/// Writes OUT/frames/NNNNNN.png, OUT/truth/NNNNNN.txt and OUT/README.txt (old frames and truth
/// removed first). Throws std::runtime_error with one line on failure.
void writeScene(const HeadScene& scene, const SceneOptions& options, const std::string& outDir);

}  // namespace headgen
