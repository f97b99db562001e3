#pragma once
// The "hard" family of cardgen: held-card sequences whose seed picks everything (card colour,
// background photograph, 3D motion path, light ramps that clip, shading across the card, camera
// noise and blur, a skin-coloured hand and arm passing over the card, a corner leaving the frame,
// skin- and card-coloured distractors). Each member switches on one difficulty over the same
// base (a card moving in 3D with perspective over a real photograph); `hard` switches on all of
// them. The same seed gives the same colour, background, path and plans in every member, so a
// failure of `hard` can be taken apart difficulty by difficulty. Frame 0 is the training frame.

#include "scene.hpp"

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace cardgen {

/// Which difficulties a member switches on.
struct HardDifficulties {
    bool fastMotion = false;   ///< faster, wider 3D motion
    bool light = false;        ///< whole-scene light ramps up to clipping and down to dim
    bool shading = false;      ///< a strong brightness gradient across the card, turning
    bool noise = false;        ///< strong camera noise and a little lens blur
    bool occluder = false;     ///< a hand and arm reaching over the card and back
    bool corner = false;       ///< one corner pushed out of the frame and back
    bool distractors = false;  ///< a card-coloured patch and a skin-coloured hand behind
};

/// What the seed picked, drawn once (see hard_scenarios.cpp for the ranges).
struct HardPlan {
    cv::Vec3b colour;  ///< RGB
    const char* colourName = "";
    int background = 0;  ///< index into hardBackgrounds()
    // Motion: per pose parameter (cx, cy, size, yaw, pitch, roll) amplitude, period, phase.
    double amplitude[6], period[6], phase[6];
    double size = 0.18;  ///< half the card's short side / frame height
    double roll0 = 0.0;
    // Light: the two extremes (peak first or trough first) and when the ramps happen (0..1).
    double peakGain = 1.8, troughGain = 0.5;
    bool peakFirst = true;
    double lightAt[6];  ///< start, up-end, hold-end, down-end, hold-end, back-end
    // Shading.
    double gradient = 0.2, gradientPhase = 0.0, gradientPeriod = 10.0;
    // Camera.
    double noiseSigma = 6.0, blurSigma = 0.6;
    // Occluder: entry side (0 right, 1 left, 2 bottom), the two points on the card it moves
    // between (card coordinates, -1..1), its window (0..1), palm size / card half height.
    int side = 0;
    const char* occluderKind = "";
    double fromU = 0, fromV = 0, toU = 0, toV = 0;
    double occluderStart = 0.3, occluderLength = 0.3, palm = 0.45;
    int skinTone = 0;
    // Corner: which one, along which axis it leaves, how far out (pixels), its window (0..1).
    int corner = 0;
    bool cornerAlongX = false;
    double cornerDepth = 30.0, cornerStart = 0.5, cornerHold = 0.1;
    // Distractors: the card-coloured patch's colour, pose (found clear of the card's path)
    // and whether a place was found; the skin hand's place and tone.
    cv::Vec3b patchColour;
    double patchHueShift = 0.0;
    bool havePatch = false;
    CardPose patch;
    HandPose backHand;
};

/// The family's photographs: paths relative to the shared data folder or absolute.
const std::vector<std::string>& hardBackgrounds();

/// True for the name of a member of the family (`hard`, `hard_light`, ...).
bool isHardScenario(const std::string& name);
/// The difficulties of a member (all off for an unknown name).
HardDifficulties hardDifficulties(const std::string& name);

/// One member for a size, length and seed.
class HardScene {
public:
    HardScene(const std::string& name, cv::Size size, int frames, std::uint32_t seed);

    FrameSpec frame(int index) const;
    const HardPlan& plan() const noexcept { return plan_; }
    /// The background candidates: the seed's pick first, then the others as fall-backs.
    std::vector<std::string> backgrounds() const;
    /// The seed's picks in words, for scenario.txt.
    std::string summary() const;

private:
    CardPose basePose(int index) const noexcept;
    CardPose pose(int index) const noexcept;
    double gain(int index) const noexcept;
    platform::CardPaint paint(const CardPose& pose, int index) const noexcept;
    bool occluderAt(int index, const vision::Quad& card, HandPose& hand) const noexcept;
    void placePatch();
    FrameSpec trainingFrame() const;

    HardDifficulties on_;
    cv::Size size_;
    int frames_;
    std::uint32_t seed_;
    double focal_;
    HardPlan plan_;
    std::vector<double> clock_;  ///< motion time (seconds) per frame: stops during rests
};

}  // namespace cardgen
