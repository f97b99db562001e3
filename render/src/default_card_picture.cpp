#include "render/default_card_picture.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <stdexcept>

namespace render {
namespace {

// Scene coordinates are fixed-point: 0..kOne across the painted area on each axis, so the
// picture keeps its composition at any size and stays integer-only (hence bit-identical on
// every machine).
constexpr int kOne = 1024;

struct Rgb {
    int r, g, b;
};

// a + (b - a) * t / kOne, t in 0..kOne.
Rgb mix(Rgb a, Rgb b, int t)
{
    t = std::clamp(t, 0, kOne);
    return {a.r + (b.r - a.r) * t / kOne, a.g + (b.g - a.g) * t / kOne,
            a.b + (b.b - a.b) * t / kOne};
}

std::uint32_t hash(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// A mountain range: the ridge height (scene v, smaller is higher) at u, through control points
// joined by straight slopes, roughened by a little hashed noise so the ridges look rocky.
struct RidgePoint {
    int u, v;
};

int ridge(const RidgePoint* points, int count, int u, std::uint32_t seed)
{
    int i = 0;
    while (i + 2 < count && u > points[i + 1].u)
        ++i;
    const RidgePoint a = points[i];
    const RidgePoint b = points[i + 1];
    const int v = a.v + (b.v - a.v) * (u - a.u) / std::max(1, b.u - a.u);
    // Noise on a coarse grid (8 scene units) keeps it from being pixel static at large sizes.
    const int cell = u / 8;
    const int n0 = static_cast<int>(hash(seed + static_cast<std::uint32_t>(cell)) % 13U);
    const int n1 = static_cast<int>(hash(seed + static_cast<std::uint32_t>(cell + 1)) % 13U);
    return v + n0 + (n1 - n0) * (u % 8) / 8 - 6;
}

constexpr RidgePoint kFarRange[] = {{-8, 520},  {90, 440},  {200, 500}, {330, 380}, {470, 470},
                                    {560, 430}, {700, 520}, {820, 400}, {950, 470}, {1040, 430}};
constexpr RidgePoint kNearRange[] = {{-8, 560},  {120, 470}, {260, 600}, {420, 600}, {600, 500},
                                     {700, 560}, {780, 620}, {900, 520}, {1040, 590}};

constexpr int kHorizon = 640;  // the lake's shore line
constexpr int kSunU = 610;
constexpr int kSunV = 420;
constexpr int kSunRadius = 70;  // in scene units of the shorter axis (see below)
constexpr int kMeadowTop = 880;

const Rgb kSkyTop{38, 62, 140};
const Rgb kSkyMiddle{150, 110, 170};
const Rgb kSkyHorizon{255, 170, 95};
const Rgb kSun{255, 240, 190};
const Rgb kFarMountain{125, 92, 145};
const Rgb kNearMountain{52, 50, 88};
const Rgb kSnow{236, 232, 245};
const Rgb kLake{30, 60, 110};
const Rgb kMeadowNear{40, 95, 45};
const Rgb kMeadowFar{95, 140, 60};
const Rgb kMat{238, 232, 218};
const Rgb kWoodDark{78, 46, 24};
const Rgb kWoodLight{128, 82, 44};

Rgb sky(int u, int v, int aspectNum, int aspectDen)
{
    Rgb c = v < kHorizon / 2 ? mix(kSkyTop, kSkyMiddle, v * kOne / (kHorizon / 2))
                             : mix(kSkyMiddle, kSkyHorizon,
                                   (v - kHorizon / 2) * kOne / (kHorizon - kHorizon / 2));
    // Distance to the sun measured in height units so the sun stays round at any aspect.
    const int du = (u - kSunU) * aspectNum / aspectDen;
    const int dv = v - kSunV;
    const int d2 = du * du + dv * dv;
    if (d2 <= kSunRadius * kSunRadius)
        return kSun;
    // Glow: falls off with the square of the distance, a fraction of the sun's colour added.
    const int glow = kOne * kSunRadius * kSunRadius / d2;  // 0..kOne
    return mix(c, kSun, glow * 3 / 4);
}

Rgb scene(int u, int v, int aspectNum, int aspectDen)
{
    if (v < kHorizon) {
        const int nearRidge = ridge(kNearRange, static_cast<int>(std::size(kNearRange)), u, 7001U);
        if (v >= nearRidge) {
            // Snow on the upper part of the high near peaks only.
            const int snowLine = 540;
            if (v < snowLine && v < nearRidge + 28 + static_cast<int>(hash(u / 6 + 99U) % 12U))
                return kSnow;
            // Darker toward the foot: the evening light is on the peaks.
            return mix(kNearMountain, Rgb{30, 30, 55}, (v - nearRidge) * kOne / 200);
        }
        const int farRidge = ridge(kFarRange, static_cast<int>(std::size(kFarRange)), u, 4242U);
        if (v >= farRidge) {
            // Haze: the far range fades into the horizon colour lower down.
            return mix(kFarMountain, kSkyHorizon, (v - farRidge) * kOne / 500);
        }
        return sky(u, v, aspectNum, aspectDen);
    }
    if (v >= kMeadowTop + static_cast<int>((u - 512) * (u - 512) / 6000)) {
        Rgb c = mix(kMeadowFar, kMeadowNear, (v - kMeadowTop) * kOne / (kOne - kMeadowTop));
        // Tufts of grass: a few brighter specks.
        if (hash(static_cast<std::uint32_t>(u / 3 * 7919 + v / 3)) % 11U == 0)
            c = mix(c, Rgb{170, 200, 90}, kOne / 2);
        return c;
    }
    // The lake mirrors the sky and mountains above the shore line, darker and bluer, broken into
    // horizontal ripples.
    const int mirrored = 2 * kHorizon - 1 - v;  // < kHorizon: no recursion past one level
    const int ripple = static_cast<int>(hash(static_cast<std::uint32_t>(v / 3 + 13)) % 9U) - 4;
    Rgb c = scene(std::clamp(u + ripple, 0, kOne - 1), std::max(0, mirrored), aspectNum, aspectDen);
    c = mix(c, kLake, kOne * 45 / 100);
    // The sun's glitter path on the water: broken streaks, wider nearer the viewer.
    const int du = (u - kSunU) * aspectNum / aspectDen;
    const int row = v / 3;
    const int halfWidth = kSunRadius / 3 + (v - kHorizon) * kSunRadius / 400 +
                          static_cast<int>(hash(static_cast<std::uint32_t>(row * 31 + 5)) % 24U);
    const int shift = static_cast<int>(hash(static_cast<std::uint32_t>(row * 17 + 3)) % 21U) - 10;
    if (hash(static_cast<std::uint32_t>(row + 777)) % 3U != 0 && du > shift - halfWidth &&
        du < shift + halfWidth)
        c = mix(c, kSun, kOne * 2 / 3);
    return c;
}

Rgb wood(int x, int y, bool vertical)
{
    // Grain along the frame's side: stripes that wander slowly.
    const int along = vertical ? y : x;
    const int across = vertical ? x : y;
    const int wobble = static_cast<int>(hash(static_cast<std::uint32_t>(along / 16)) % 5U);
    const int grain =
        static_cast<int>(hash(static_cast<std::uint32_t>(across * 3 + wobble)) % 100U);
    return mix(kWoodDark, kWoodLight, grain * kOne / 160);
}

}  // namespace

vision::ImageBuffer defaultCardPicture(vision::Size size)
{
    vision::ImageBuffer image(size.width, size.height, vision::PixelFormat::RGB24);
    const vision::ImageView view = image.view();
    const int shorter = std::min(size.width, size.height);
    const int frame = std::max(1, shorter / 14);
    const int mat = std::max(1, shorter / 28);
    const int inset = frame + mat;
    const int sceneW = std::max(1, size.width - 2 * inset);
    const int sceneH = std::max(1, size.height - 2 * inset);
    for (int y = 0; y < size.height; ++y) {
        std::uint8_t* p = view.row(y);
        for (int x = 0; x < size.width; ++x) {
            const int edge =
                std::min(std::min(x, size.width - 1 - x), std::min(y, size.height - 1 - y));
            Rgb c;
            if (edge < frame) {
                // Mitred corners: the side nearer the pixel owns it.
                const bool vertical =
                    std::min(x, size.width - 1 - x) < std::min(y, size.height - 1 - y);
                c = wood(x, y, vertical);
                if (edge == 0 || edge == frame - 1)
                    c = mix(c, Rgb{20, 12, 6}, kOne / 2);  // the frame's outline
            } else if (edge < inset) {
                c = kMat;
            } else {
                const int u = (x - inset) * kOne / sceneW;
                const int v = (y - inset) * kOne / sceneH;
                c = scene(u, v, sceneW, sceneH);
            }
            *p++ = static_cast<std::uint8_t>(std::clamp(c.r, 0, 255));
            *p++ = static_cast<std::uint8_t>(std::clamp(c.g, 0, 255));
            *p++ = static_cast<std::uint8_t>(std::clamp(c.b, 0, 255));
        }
    }
    return image;
}

}  // namespace render
