#include "platform/card_scene_source.hpp"

#include "noise_hash.hpp"

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

struct ChannelLayout {
    int bytesPerPixel;
    int r, g, b;  // byte offsets within a pixel
};

constexpr ChannelLayout layoutOf(vision::PixelFormat f) noexcept
{
    switch (f) {
        case vision::PixelFormat::RGB24:
            return {3, 0, 1, 2};
        case vision::PixelFormat::BGR24:
            return {3, 2, 1, 0};
        case vision::PixelFormat::XRGB8888:
            return {4, 2, 1, 0};
        default:
            return {0, 0, 0, 0};
    }
}

}  // namespace

struct CardSceneSource::Pose {
    std::array<double, 8> corners;  ///< x0, y0, ... clockwise from top-left
    std::array<double, 9> toCard;   ///< homography: pixel -> card coordinates in [-1, 1]^2
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
    if (layoutOf(format_).bytesPerPixel == 0)
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
    pathX_ = std::max(0.0, 0.5 * (w - 1.0) - maxR - kMarginPx);
    pathY_ = std::max(0.0, 0.5 * (h - 1.0) - maxR - kMarginPx);

    char colour[48];
    std::snprintf(colour, sizeof colour, "card #%02x%02x%02x", options_.red, options_.green,
                  options_.blue);
    description_ = std::string(inner_->description()) + " + " + colour;
    corners_ = cornersFor(0);
}

CardSceneSource::Pose CardSceneSource::poseFor(std::uint64_t sequence) const noexcept
{
    const double t = static_cast<double>(sequence) / 30.0;
    const double yaw = kMaxYaw * std::sin(kTwoPi * t / 7.3);
    const double pitch = kMaxPitch * std::sin(kTwoPi * t / 9.1 + 1.0);
    const double roll = kMaxRoll * std::sin(kTwoPi * t / 11.7 + 0.5);
    const double cx = 0.5 * (size_.width - 1) + pathX_ * std::sin(kTwoPi * t / 13.0 + 0.3);
    const double cy = 0.5 * (size_.height - 1) + pathY_ * std::sin(kTwoPi * t / 8.9 + 1.7);

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
        cx * depth_,
        focal_ * r1[1] * hw + cy * r1[2] * hw,
        focal_ * r2[1] * hh + cy * r2[2] * hh,
        cy * depth_,
        r1[2] * hw,
        r2[2] * hh,
        depth_,
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
    // Inverse by the adjugate (the scale of a homography does not matter).
    pose.toCard = {
        m[4] * m[8] - m[5] * m[7], m[2] * m[7] - m[1] * m[8], m[1] * m[5] - m[2] * m[4],
        m[5] * m[6] - m[3] * m[8], m[0] * m[8] - m[2] * m[6], m[2] * m[3] - m[0] * m[5],
        m[3] * m[7] - m[4] * m[6], m[1] * m[6] - m[0] * m[7], m[0] * m[4] - m[1] * m[3],
    };

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

std::array<Point2f, 4> CardSceneSource::cornersFor(std::uint64_t sequence) const noexcept
{
    const Pose pose = poseFor(sequence);
    std::array<Point2f, 4> out;
    for (int i = 0; i < 4; ++i)
        out[i] = {static_cast<float>(pose.corners[2 * i]),
                  static_cast<float>(pose.corners[2 * i + 1])};
    return out;
}

bool CardSceneSource::drawCard(std::uint64_t sequence, vision::ImageView image) const noexcept
{
    if (image.data == nullptr || image.size() != size_ || image.format != format_)
        return false;
    const ChannelLayout layout = layoutOf(format_);
    const Pose pose = poseFor(sequence);

    // Edge functions: signed distance in pixels, positive inside (the corners are clockwise on
    // screen, y down).
    double nx[4], ny[4], c0[4];
    double minX = 1e9, maxX = -1e9, minY = 1e9, maxY = -1e9;
    for (int i = 0; i < 4; ++i) {
        const double px = pose.corners[2 * i], py = pose.corners[2 * i + 1];
        const double qx = pose.corners[(2 * i + 2) % 8], qy = pose.corners[(2 * i + 3) % 8];
        const double len = std::max(std::hypot(qx - px, qy - py), 1e-9);
        nx[i] = -(qy - py) / len;
        ny[i] = (qx - px) / len;
        c0[i] = -(nx[i] * px + ny[i] * py);
        minX = std::min(minX, px);
        maxX = std::max(maxX, px);
        minY = std::min(minY, py);
        maxY = std::max(maxY, py);
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(minX)) - 1);
    const int x1 = std::min(size_.width - 1, static_cast<int>(std::ceil(maxX)) + 1);
    const int y0 = std::max(0, static_cast<int>(std::floor(minY)) - 1);
    const int y1 = std::min(size_.height - 1, static_cast<int>(std::ceil(maxY)) + 1);

    // Subsample offsets of a 4x4 grid within the pixel; all samples lie within 0.54 px of the
    // centre, so pixels farther than that from every edge need no sampling.
    constexpr double kOffsets[4] = {-0.375, -0.125, 0.125, 0.375};
    constexpr double kSure = 0.54;
    const double base[3] = {static_cast<double>(options_.red), static_cast<double>(options_.green),
                            static_cast<double>(options_.blue)};
    const int noiseSpan = 2 * std::max(0, options_.noise) + 1;
    const auto& hinv = pose.toCard;
    const auto seq32 = static_cast<std::uint32_t>(sequence);

    for (int y = y0; y <= y1; ++y) {
        std::uint8_t* p = image.row(y) + static_cast<std::ptrdiff_t>(x0) * layout.bytesPerPixel;
        for (int x = x0; x <= x1; ++x, p += layout.bytesPerPixel) {
            double d[4];
            double dmin = 1e9;
            for (int i = 0; i < 4; ++i) {
                d[i] = nx[i] * x + ny[i] * y + c0[i];
                dmin = std::min(dmin, d[i]);
            }
            if (dmin <= -kSure)
                continue;
            int alpha = 256;
            if (dmin < kSure) {
                int inside = 0;
                for (const double oy : kOffsets)
                    for (const double ox : kOffsets) {
                        bool in = true;
                        for (int i = 0; i < 4 && in; ++i)
                            in = d[i] + nx[i] * ox + ny[i] * oy >= 0.0;
                        inside += in;
                    }
                if (inside == 0)
                    continue;
                alpha = inside * 16;
            }
            // Card coordinates of the pixel for its shading.
            const double w = hinv[6] * x + hinv[7] * y + hinv[8];
            const double u = std::clamp((hinv[0] * x + hinv[1] * y + hinv[2]) / w, -1.0, 1.0);
            const double v = std::clamp((hinv[3] * x + hinv[4] * y + hinv[5]) / w, -1.0, 1.0);
            const double light = pose.brightness + pose.gradientU * u + pose.gradientV * v;
            const int noise = static_cast<int>(noiseHash(static_cast<std::uint32_t>(x),
                                                         static_cast<std::uint32_t>(y), seq32) %
                                               static_cast<std::uint32_t>(noiseSpan)) -
                              noiseSpan / 2;
            const int offsets[3] = {layout.r, layout.g, layout.b};
            for (int c = 0; c < 3; ++c) {
                const int card =
                    std::clamp(static_cast<int>(base[c] * light + 0.5) + noise, 0, 255);
                std::uint8_t& dst = p[offsets[c]];
                dst = static_cast<std::uint8_t>(dst + (((card - dst) * alpha) >> 8));
            }
        }
    }
    return true;
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
                                 static_cast<std::size_t>(layoutOf(format_).bytesPerPixel);
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
