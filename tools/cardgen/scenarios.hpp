#pragma once
// The named card sequences of cardgen: each one stresses one thing the card tracker must survive
// (perspective motion, light ramps with clipping, sensor noise, gain steps, a hand over the card, a
// corner leaving the frame, fast interlaced motion, a distractor of similar colour, losing the card
// and getting it back), and the hard family (hard_scenarios.hpp) whose seed picks colour,
// background and every difficulty. Frame 0 of every sequence is the training frame: the card
// fills the view.

#include "hard_scenarios.hpp"
#include "scene.hpp"

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace cardgen {

struct ScenarioInfo {
    const char* name;
    const char* description;  ///< one paragraph for scenario.txt and --list
    /// Backgrounds to try in order: relative paths are under the shared data folder, absolute
    /// ones are system files (Debian's opencv-doc images); the first readable one is used.
    std::vector<std::string> backgrounds;
};

/// Every scenario, in a fixed order.
const std::vector<ScenarioInfo>& scenarios();
/// Null when there is no scenario of that name.
const ScenarioInfo* findScenario(const std::string& name);

inline constexpr int kDefaultFrames = 150;  ///< 5 s at 30 frames per second

/// The scene of one scenario for a given frame size, length and seed. The timeline (rests,
/// motion phases, occluder phases) scales with the length; speeds are per frame at 30 fps.
class Scenario {
public:
    /// Throws std::runtime_error for an unknown name, fewer than 2 frames or a frame smaller than
    /// 64x48.
    Scenario(const std::string& name, cv::Size size, int frames, std::uint32_t seed);

    const ScenarioInfo& info() const noexcept { return *info_; }
    int frames() const noexcept { return frames_; }
    cv::Size size() const noexcept { return size_; }
    /// Everything in frame `index` (0 .. frames-1); spec.card false when no card is in view.
    FrameSpec frame(int index) const;
    /// Background candidates in order (the hard family's start with the seed's pick).
    std::vector<std::string> backgrounds() const;
    /// What the seed picked, in words ("" for scenarios whose seed only varies phases and noise).
    std::string choices() const;

private:
    int at(int frameOf150) const noexcept;  ///< a timeline mark scaled to this length
    CardPose wander(double tSec, double amplitude) const noexcept;
    FrameSpec cardFrame(const CardPose& pose, cv::Vec3b rgb, int index) const;
    FrameSpec trainingFrame(cv::Vec3b rgb) const;

    const ScenarioInfo* info_;
    cv::Size size_;
    int frames_;
    std::uint32_t seed_;
    double focal_;
    double phase_[8];
    std::shared_ptr<const HardScene> hard_;  ///< the hard family's scene, else null
};

}  // namespace cardgen
