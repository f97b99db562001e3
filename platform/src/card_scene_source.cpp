#include "platform/card_scene_source.hpp"

#include "platform/card_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <stdexcept>

namespace platform {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kA5Aspect = 210.0 / 148.0;  // long side / short side
// Gentle 3D motion: peak yaw, pitch and roll in radians (about 20, 17 and 14 degrees).
constexpr double kMaxYaw = 0.35;
constexpr double kMaxPitch = 0.30;
constexpr double kMaxRoll = 0.25;
constexpr double kMarginPx = 2.0;  // the card's corners keep this far from the frame's border

}  // namespace

struct CardSceneSource::Pose {
    std::array<double, 8> corners;  ///< x0, y0, ... clockwise from top-left
    double gradientU;               ///< brightness slope along the card's u (times shading)
    double gradientV;
    double brightness;  ///< brightness at the card centre (1 = nominal colour)
};

CardSceneSource::CardSceneSource(std::unique_ptr<FrameSource> inner,
                                 const CardSceneOptions& options)
    : inner_(std::move(inner)), options_(options)
{
    if (!inner_)
        throw std::runtime_error("card: no inner source to draw the card over");
    size_ = inner_->size();
    format_ = inner_->format();
    if (vision::rgbLayout(format_).bytesPerPixel == 0)
        throw std::runtime_error(std::string("card: inner source format ") +
                                 vision::pixelFormatName(format_) +
                                 " unsupported (needs RGB24, BGR24 or XRGB8888)");
    if (size_.width < 32 || size_.height < 32)
        throw std::runtime_error("card: inner frames " + std::to_string(size_.width) + "x" +
                                 std::to_string(size_.height) + " too small (32x32 at least)");
    buffer_ = vision::ImageBuffer(size_.width, size_.height, format_);

    const double w = size_.width;
    const double h = size_.height;
    const double fraction = std::clamp(options_.heightFraction, 0.05, 0.6);
    halfHeight_ = 0.5 * fraction * h;
    halfWidth_ = options_.portrait ? halfHeight_ / kA5Aspect : halfHeight_ * kA5Aspect;
    focal_ = 0.9 * std::max(w, h);  // a ~60 degree lens
    depth_ = focal_;                // so one card unit is one pixel when facing the camera

    // Any corner projects within maxR of the centre: |rotated corner| = half diagonal, and its
    // depth is at least depth - half diagonal. Shrink the card if that would not fit the frame.
    const double limit = 0.5 * std::min(w, h) - kMarginPx - 1.0;
    double halfDiag = std::hypot(halfWidth_, halfHeight_);
    double maxR = focal_ * halfDiag / (depth_ - halfDiag);
    if (maxR > 0.9 * limit) {
        const double target = 0.9 * limit;
        const double scale = (target * depth_ / (focal_ + target)) / halfDiag;
        halfWidth_ *= scale;
        halfHeight_ *= scale;
        halfDiag *= scale;
        maxR = focal_ * halfDiag / (depth_ - halfDiag);
    }
    // The path's centre where asked, moved in until the card fits around it; the swing is what
    // room is left on the nearer side.
    const double reachX = std::max(0.0, 0.5 * (w - 1.0) - maxR - kMarginPx);
    const double reachY = std::max(0.0, 0.5 * (h - 1.0) - maxR - kMarginPx);
    centreX_ = std::clamp(std::clamp(options_.pathCentreX, 0.0, 1.0) * (w - 1.0),
                          0.5 * (w - 1.0) - reachX, 0.5 * (w - 1.0) + reachX);
    centreY_ = std::clamp(std::clamp(options_.pathCentreY, 0.0, 1.0) * (h - 1.0),
                          0.5 * (h - 1.0) - reachY, 0.5 * (h - 1.0) + reachY);
    pathX_ = reachX - std::abs(centreX_ - 0.5 * (w - 1.0));
    pathY_ = reachY - std::abs(centreY_ - 0.5 * (h - 1.0));

    char colour[48];
    std::snprintf(colour, sizeof colour, "card #%02x%02x%02x", options_.red, options_.green,
                  options_.blue);
    description_ = std::string(inner_->description()) + " + " + colour;
    corners_ = cornersFor(0);
}

CardSceneSource::Pose CardSceneSource::poseFor(std::uint64_t sequence) const noexcept
{
    // The training intro holds the card still, as a person does before `card train`: centred,
    // facing the camera and large enough to cover the central half of the view. It then eases
    // into the path over as many frames again (the path's time starts when the intro ends, so the
    // path is the same with or without an intro).
    const auto intro = static_cast<std::uint64_t>(std::max(0, options_.introFrames));
    const double t = sequence < intro ? 0.0 : static_cast<double>(sequence - intro) / 30.0;
    double yaw = kMaxYaw * std::sin(kTwoPi * t / 7.3);
    double pitch = kMaxPitch * std::sin(kTwoPi * t / 9.1 + 1.0);
    double roll = kMaxRoll * std::sin(kTwoPi * t / 11.7 + 0.5);
    double cx = centreX_ + pathX_ * std::sin(kTwoPi * t / 13.0 + 0.3);
    double cy = centreY_ + pathY_ * std::sin(kTwoPi * t / 8.9 + 1.7);
    double depth = depth_;
    if (intro > 0 && sequence < 2 * intro) {
        // Held pose: centred, square to the camera, its half-height 0.34 of the frame height.
        const double heldDepth = focal_ * halfHeight_ / (0.34 * size_.height);
        const double x = sequence < intro
                             ? 0.0
                             : static_cast<double>(sequence - intro) / static_cast<double>(intro);
        const double w = x * x * (3.0 - 2.0 * x);  // smoothstep: no jerk at either end
        yaw *= w;
        pitch *= w;
        roll *= w;
        cx = 0.5 * (size_.width - 1) + (cx - 0.5 * (size_.width - 1)) * w;
        cy = 0.5 * (size_.height - 1) + (cy - 0.5 * (size_.height - 1)) * w;
        depth = heldDepth + (depth_ - heldDepth) * w;
    }

    // R = Rz(roll) * Ry(yaw) * Rx(pitch); only its first two columns (the card's u and v axes)
    // and the normal matter.
    const double cr = std::cos(roll), sr = std::sin(roll);
    const double cyw = std::cos(yaw), syw = std::sin(yaw);
    const double cp = std::cos(pitch), sp = std::sin(pitch);
    // Ry * Rx columns.
    const double a[3] = {cyw, 0.0, -syw};           // x axis
    const double b[3] = {syw * sp, cp, cyw * sp};   // y axis
    const double n[3] = {syw * cp, -sp, cyw * cp};  // normal
    auto rz = [&](const double v[3], double out[3]) {
        out[0] = cr * v[0] - sr * v[1];
        out[1] = sr * v[0] + cr * v[1];
        out[2] = v[2];
    };
    double r1[3], r2[3], nn[3];
    rz(a, r1);
    rz(b, r2);
    rz(n, nn);

    // Homography card (u, v in [-1, 1]) -> pixel: K [r1*hw  r2*hh  (0,0,depth)].
    const double hw = halfWidth_, hh = halfHeight_;
    const double m[9] = {
        focal_ * r1[0] * hw + cx * r1[2] * hw,
        focal_ * r2[0] * hh + cx * r2[2] * hh,
        cx * depth,
        focal_ * r1[1] * hw + cy * r1[2] * hw,
        focal_ * r2[1] * hh + cy * r2[2] * hh,
        cy * depth,
        r1[2] * hw,
        r2[2] * hh,
        depth,
    };
    Pose pose{};
    const double us[4] = {-1.0, 1.0, 1.0, -1.0};
    const double vs[4] = {-1.0, -1.0, 1.0, 1.0};
    for (int i = 0; i < 4; ++i) {
        const double x = m[0] * us[i] + m[1] * vs[i] + m[2];
        const double y = m[3] * us[i] + m[4] * vs[i] + m[5];
        const double z = m[6] * us[i] + m[7] * vs[i] + m[8];
        pose.corners[2 * i] = x / z;
        pose.corners[2 * i + 1] = y / z;
    }

    // Lighting: a gradient turning slowly across the card, and a little darker when tilted away.
    // |0.6/sqrt2 * (cos u + sin v)| <= 0.6 and the tilt term is in [-0.4, 0], so the brightness
    // stays within 1 +- shading.
    const double phi = kTwoPi * t / 10.0;
    const double s = options_.shading;
    pose.gradientU = s * 0.6 / std::numbers::sqrt2 * std::cos(phi);
    pose.gradientV = s * 0.6 / std::numbers::sqrt2 * std::sin(phi);
    pose.brightness = 1.0 - s * std::min(0.4, 4.0 * (1.0 - std::abs(nn[2])));
    return pose;
}

vision::Quad CardSceneSource::cornersFor(std::uint64_t sequence) const noexcept
{
    const Pose pose = poseFor(sequence);
    vision::Quad out;
    for (int i = 0; i < 4; ++i)
        out[i] = {static_cast<float>(pose.corners[2 * i]),
                  static_cast<float>(pose.corners[2 * i + 1])};
    return out;
}

bool CardSceneSource::drawCard(std::uint64_t sequence, vision::ImageView image) const noexcept
{
    if (image.data == nullptr || image.size() != size_ || image.format != format_)
        return false;
    const Pose pose = poseFor(sequence);
    CardPaint paint;
    paint.red = options_.red;
    paint.green = options_.green;
    paint.blue = options_.blue;
    paint.brightness = pose.brightness;
    paint.gradientU = pose.gradientU;
    paint.gradientV = pose.gradientV;
    paint.noise = options_.noise;
    paint.noiseSeed = static_cast<std::uint32_t>(sequence);
    vision::Quad quad;
    for (int i = 0; i < 4; ++i)
        quad[i] = {static_cast<float>(pose.corners[2 * i]),
                   static_cast<float>(pose.corners[2 * i + 1])};
    return drawCardQuad(image, quad, paint);
}

SourceStatus CardSceneSource::next(vision::Frame& frame) noexcept
{
    vision::Frame in;
    const SourceStatus status = inner_->next(in);
    if (status != SourceStatus::Ok)
        return status;
    if (in.image.data == nullptr || in.image.size() != size_ || in.image.format != format_) {
        std::snprintf(lastError_, sizeof lastError_,
                      "card: inner frame %dx%d %s differs from the announced %dx%d %s",
                      in.image.width, in.image.height, vision::pixelFormatName(in.image.format),
                      size_.width, size_.height, vision::pixelFormatName(format_));
        return SourceStatus::Lost;
    }
    lastError_[0] = '\0';
    const vision::ImageView out = buffer_.view();
    const std::size_t rowBytes = static_cast<std::size_t>(size_.width) *
                                 static_cast<std::size_t>(vision::rgbLayout(format_).bytesPerPixel);
    for (int y = 0; y < size_.height; ++y)
        std::memcpy(out.row(y), in.image.row(y), rowBytes);
    drawCard(in.sequence, out);
    corners_ = cornersFor(in.sequence);
    frame.image = out;
    frame.sequence = in.sequence;
    frame.timestampNs = in.timestampNs;
    return SourceStatus::Ok;
}

const char* CardSceneSource::lastError() const noexcept
{
    return lastError_[0] != '\0' ? lastError_ : inner_->lastError();
}

}  // namespace platform
