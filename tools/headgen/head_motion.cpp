// Poses and expressions of headgen frames (head_motion.hpp).
#include "head_motion.hpp"

#include "shape_synthesis.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace headgen {

HandMode handModeNamed(const std::string& name)
{
    if (name == "none")
        return HandMode::None;
    if (name == "some")
        return HandMode::Some;
    if (name == "all")
        return HandMode::All;
    throw std::invalid_argument("--hand " + name + ": expected none, some or all");
}

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kFps = 30.0;

/// A smooth wave in [-1, 1]: two sines of random phase, 0.1-0.35 and 0.35-0.8 Hz.
struct Wave {
    double f1, f2, p1, p2;
    explicit Wave(std::mt19937& r)
    {
        std::uniform_real_distribution<double> low(0.1, 0.35), high(0.35, 0.8), phase(0, kTwoPi);
        f1 = low(r), f2 = high(r), p1 = phase(r), p2 = phase(r);
    }
    double at(double seconds) const
    {
        return 0.7 * std::sin(kTwoPi * f1 * seconds + p1) +
               0.3 * std::sin(kTwoPi * f2 * seconds + p2);
    }
};

/// Maps a wave value in [-1, 1] onto [low, high].
double within(double wave, double low, double high)
{
    return low + 0.5 * (wave + 1) * (high - low);
}

double baseScale(cv::Size size)
{
    return 0.2 * std::min(size.width, size.height);
}

FramePlan singleFrame(const MotionOptions& o, std::mt19937& r, int textures, int backgrounds)
{
    std::uniform_real_distribution<double> unit(-1, 1);
    FramePlan f;
    f.texture = std::uniform_int_distribution<int>(0, textures - 1)(r);
    f.background = std::uniform_int_distribution<int>(0, backgrounds - 1)(r);
    f.pose.yawDeg = o.maxYawDeg * unit(r);
    f.pose.pitchDeg = o.maxPitchDeg * unit(r);
    f.pose.rollDeg = o.maxRollDeg * unit(r);
    f.pose.scale = baseScale(o.size) * (1 + 0.2 * unit(r));
    f.pose.translation = {o.size.width * (0.5 + 0.2 * unit(r)),
                          o.size.height * (0.5 + 0.12 * unit(r))};
    for (std::size_t j = 0; j < f.pose.animation.size(); ++j)
        f.pose.animation[j] = static_cast<float>(
            within(unit(r), aam::kAnimationRange[j].low, aam::kAnimationRange[j].high));
    f.handAngleDeg = 40 * unit(r);
    f.handSide = unit(r);
    return f;
}

}  // namespace

std::vector<FramePlan> planFrames(const MotionOptions& o, int textures, int backgrounds)
{
    if (textures < 1 || backgrounds < 1 || o.frames < 1)
        throw std::invalid_argument("planFrames: nothing to draw from");
    std::mt19937 r(o.seed);
    std::vector<FramePlan> plans;
    if (!o.sequence) {
        for (int i = 0; i < o.frames; ++i) {
            plans.push_back(singleFrame(o, r, textures, backgrounds));
            plans.back().hand = o.hand == HandMode::All || (o.hand == HandMode::Some && i % 2);
        }
        return plans;
    }
    const FramePlan start = singleFrame(o, r, textures, backgrounds);
    const Wave yaw(r), pitch(r), roll(r), scale(r), x(r), y(r), jaw(r);
    std::vector<Wave> units;
    for (std::size_t j = 1; j < start.pose.animation.size(); ++j)
        units.emplace_back(r);
    for (int i = 0; i < o.frames; ++i) {
        const double s = i / kFps;
        FramePlan f = start;
        f.pose.yawDeg = o.maxYawDeg * yaw.at(s);
        f.pose.pitchDeg = o.maxPitchDeg * pitch.at(s);
        f.pose.rollDeg = o.maxRollDeg * roll.at(s);
        f.pose.scale = baseScale(o.size) * (1 + 0.15 * scale.at(s));
        f.pose.translation = {o.size.width * (0.5 + 0.15 * x.at(s)),
                              o.size.height * (0.5 + 0.08 * y.at(s))};
        // Talking: the jaw opens and closes, resting closed part of the time.
        f.pose.animation[0] = static_cast<float>(std::max(0.0, jaw.at(s)));
        for (std::size_t j = 1; j < f.pose.animation.size(); ++j)
            f.pose.animation[j] =
                static_cast<float>(0.6 * within(units[j - 1].at(s), aam::kAnimationRange[j].low,
                                                aam::kAnimationRange[j].high));
        f.hand = o.hand == HandMode::All ||
                 (o.hand == HandMode::Some && 3 * i >= o.frames && 3 * i < 2 * o.frames);
        plans.push_back(f);
    }
    return plans;
}

}  // namespace headgen
