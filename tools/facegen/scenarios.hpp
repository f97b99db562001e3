#pragma once
// The named facegen sequences and the smooth paths of their moving faces. A Scenario samples, from
// its seed, which IMM faces move and how (centre, size and roll as smooth functions of time), and
// re-samples until no two faces - moving or the background's static ones - overlap by more than
// 30% of the smaller box in any frame, and the faces that should stay in view do.

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace facegen {

struct ScenarioInfo {
    const char* name;
    const char* description;  ///< one paragraph for README.txt and --list
    const char* background;   ///< photograph under the shared data folder
    int movingFaces;
};

/// Every scenario, in a fixed order.
const std::vector<ScenarioInfo>& scenarios();
/// Null when there is no scenario of that name.
const ScenarioInfo* findScenario(const std::string& name);

inline constexpr int kDefaultFrames = 300;  ///< 10 s at 30 frames per second
inline constexpr double kMaxOverlap = 0.3;  ///< intersection over the smaller box

/// One face in one frame, in frame pixels (pixel centres at integer coordinates).
struct FaceState {
    int id = 0;
    double cx = 0, cy = 0;
    double size = 0;     ///< side of the square box, Viola-Jones convention
    double rollDeg = 0;  ///< clockwise on screen positive
    bool moving = true;
    int source = -1;  ///< index into Scenario::faceSources() (moving faces)
};

/// Intersection of the two axis-aligned square boxes over the smaller one's area.
double overlapOfSmaller(const FaceState& a, const FaceState& b) noexcept;
/// True when any part of the face's square box lies within the frame.
bool boxTouchesFrame(const FaceState& f, cv::Size size) noexcept;

/// Deterministic uniform numbers (splitmix64), the same on every platform.
class Random {
public:
    explicit Random(std::uint64_t seed) noexcept : state_(seed) {}
    std::uint64_t next() noexcept;
    double uniform(double lo, double hi) noexcept;  ///< in [lo, hi)
    int below(int n) noexcept;                      ///< in [0, n)

private:
    std::uint64_t state_;
};

/// One moving face's path over the sequence, u = frame / (frames - 1) in [0, 1].
struct FacePath {
    int source = -1;
    double u0 = 0, u1 = 1;      ///< in the scene only for u0 <= u <= u1
    cv::Point2d from, via, to;  ///< quadratic Bezier base path over the life
    double wobbleX = 0, wobbleY = 0, wobbleFx = 0, wobbleFy = 0, wobblePx = 0, wobblePy = 0;
    double size = 100, sizeAmp = 0, sizeFreq = 0, sizePhase = 0;
    double rollAmp = 0, rollFreq = 0, rollPhase = 0, rollBias = 0;
    bool stayInView = true;  ///< whole box inside the frame all life long
};

class Scenario {
public:
    /// `sources` are the candidate IMM faces (their count only matters; picks are indices);
    /// `staticFaces` are the background's faces, kept clear of. Throws std::runtime_error for an
    /// unknown name, fewer than 2 frames, a frame smaller than 160x120, or when no path set
    /// satisfies the constraints.
    Scenario(const std::string& name, cv::Size size, int frames, std::uint32_t seed,
             const std::vector<std::string>& sources, std::vector<FaceState> staticFaces);

    const ScenarioInfo& info() const noexcept { return *info_; }
    int frames() const noexcept { return frames_; }
    cv::Size size() const noexcept { return size_; }
    const std::vector<FacePath>& paths() const noexcept { return paths_; }
    const std::vector<std::string>& faceSources() const noexcept { return sources_; }
    const std::vector<FaceState>& staticFaces() const noexcept { return static_; }
    int attempts() const noexcept { return attempts_; }  ///< paths sampled in all

    /// Moving faces in view in frame `index` (their box touches the frame), ordered far to near
    /// (small to large) as they are drawn, then the static faces.
    std::vector<FaceState> frame(int index) const;

private:
    FaceState stateOf(int id, double u) const noexcept;
    /// Face i's path, of a person not among `persons`.
    FacePath samplePath(Random& rng, int i, const std::vector<std::string>& persons) const;
    /// Whether paths_ keep every constraint in every frame.
    bool acceptable() const;

    const ScenarioInfo* info_;
    cv::Size size_;
    int frames_;
    std::vector<std::string> sources_;
    std::vector<FaceState> static_;
    std::vector<FacePath> paths_;
    int attempts_ = 0;
};

}  // namespace facegen
