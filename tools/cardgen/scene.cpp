#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace cardgen {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

vision::ImageView viewOf(cv::Mat& bgr) noexcept
{
    return {bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step[0]),
            vision::PixelFormat::BGR24};
}

/// Distance from p to the segment a-b.
double segmentDistance(double px, double py, double ax, double ay, double bx, double by) noexcept
{
    const double vx = bx - ax, vy = by - ay;
    const double len2 = vx * vx + vy * vy;
    const double t = len2 > 0 ? std::clamp(((px - ax) * vx + (py - ay) * vy) / len2, 0.0, 1.0) : 0;
    return std::hypot(px - ax - t * vx, py - ay - t * vy);
}

}  // namespace

vision::Quad projectCard(const CardPose& pose, double focal) noexcept
{
    const double cr = std::cos(pose.roll), sr = std::sin(pose.roll);
    const double cyw = std::cos(pose.yaw), syw = std::sin(pose.yaw);
    const double cp = std::cos(pose.pitch), sp = std::sin(pose.pitch);
    // R = Rz(roll) Ry(yaw) Rx(pitch): the card's u and v axes in camera coordinates.
    const double a[3] = {cyw, 0.0, -syw};
    const double b[3] = {syw * sp, cp, cyw * sp};
    const double r1[3] = {cr * a[0] - sr * a[1], sr * a[0] + cr * a[1], a[2]};
    const double r2[3] = {cr * b[0] - sr * b[1], sr * b[0] + cr * b[1], b[2]};
    const double hh = pose.halfHeight, hw = pose.halfHeight * kCardAspect;
    const double depth = focal;  // one card unit is one pixel at the centre when facing the camera
    const double us[4] = {-1.0, 1.0, 1.0, -1.0};
    const double vs[4] = {-1.0, -1.0, 1.0, 1.0};
    vision::Quad q;
    for (int i = 0; i < 4; ++i) {
        const double X = r1[0] * hw * us[i] + r2[0] * hh * vs[i];
        const double Y = r1[1] * hw * us[i] + r2[1] * hh * vs[i];
        const double Z = r1[2] * hw * us[i] + r2[2] * hh * vs[i] + depth;
        q[i] = {static_cast<float>(pose.cx + focal * X / Z),
                static_cast<float>(pose.cy + focal * Y / Z)};
    }
    return q;
}

platform::CardPaint shadeCard(const CardPose& pose, cv::Vec3b rgb, double timeSec,
                              std::uint32_t noiseSeed) noexcept
{
    platform::CardPaint p;
    p.red = rgb[0];
    p.green = rgb[1];
    p.blue = rgb[2];
    // Tilted away from the light (roughly the camera) it darkens, by up to 10 %; a gradient of
    // +-6 % turns slowly across it (light from one side).
    const double facing = std::cos(pose.yaw) * std::cos(pose.pitch);
    const double phi = kTwoPi * timeSec / 10.0;
    p.brightness = 1.0 - 0.10 * std::min(1.0, 4.0 * (1.0 - facing));
    p.gradientU = 0.06 * std::cos(phi);
    p.gradientV = 0.06 * std::sin(phi);
    p.noise = 3;
    p.noiseSeed = noiseSeed;
    return p;
}

cv::Mat loadBackground(const std::string& path, cv::Size size)
{
    const cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
    if (img.empty())
        throw std::runtime_error("background " + path + ": cannot read (missing or not an image)");
    // Scale to cover the frame, then crop the centre: no borders, no distortion.
    const double scale = std::max(static_cast<double>(size.width) / img.cols,
                                  static_cast<double>(size.height) / img.rows);
    cv::Mat scaled;
    cv::resize(img, scaled,
               cv::Size(std::max(size.width, static_cast<int>(std::ceil(img.cols * scale))),
                        std::max(size.height, static_cast<int>(std::ceil(img.rows * scale)))),
               0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
    const cv::Rect crop((scaled.cols - size.width) / 2, (scaled.rows - size.height) / 2, size.width,
                        size.height);
    return scaled(crop).clone();
}

void drawHand(cv::Mat& bgr, const HandPose& hand)
{
    const double r = hand.radius;
    const double dx = std::cos(hand.angle), dy = std::sin(hand.angle);  // towards the fingertips
    const double px = -dy, py = dx;                                     // across the hand
    // Fingers: four capsules fanning out of the palm, and a thumb at the side.
    struct Capsule {
        double ax, ay, bx, by, radius;
    } caps[5];
    const double offsets[4] = {-0.69, -0.23, 0.23, 0.69};
    const double lengths[4] = {1.25, 1.6, 1.55, 1.2};
    for (int k = 0; k < 4; ++k) {
        const double ox = hand.x + dx * 0.6 * r + px * offsets[k] * r;
        const double oy = hand.y + dy * 0.6 * r + py * offsets[k] * r;
        const double spread = 0.08 * offsets[k] / 0.66;
        const double fx = dx * std::cos(spread) - dy * std::sin(spread);
        const double fy = dy * std::cos(spread) + dx * std::sin(spread);
        caps[k] = {ox, oy, ox + fx * lengths[k] * r, oy + fy * lengths[k] * r, 0.25 * r};
    }
    {
        const double ox = hand.x + px * 0.75 * r, oy = hand.y + py * 0.75 * r;
        const double a = 0.9;  // the thumb points 50 degrees out of the hand's axis
        const double tx = dx * std::cos(a) + px * std::sin(a);
        const double ty = dy * std::cos(a) + py * std::sin(a);
        caps[4] = {ox, oy, ox + tx * 1.0 * r, oy + ty * 1.0 * r, 0.24 * r};
    }
    // The arm: a capsule from the wrist backwards (only when asked: the plain hand is unchanged).
    const bool arm = hand.armLength > 0.0;
    const Capsule forearm{hand.x - dx * 0.5 * r, hand.y - dy * 0.5 * r,
                          hand.x - dx * (0.5 + hand.armLength) * r,
                          hand.y - dy * (0.5 + hand.armLength) * r, 0.72 * r};
    const double reach = 2.6 * r;
    int x0 = std::max(0, static_cast<int>(hand.x - reach));
    int x1 = std::min(bgr.cols - 1, static_cast<int>(hand.x + reach) + 1);
    int y0 = std::max(0, static_cast<int>(hand.y - reach));
    int y1 = std::min(bgr.rows - 1, static_cast<int>(hand.y + reach) + 1);
    if (arm) {
        const double ex = forearm.bx, ey = forearm.by, er = forearm.radius + 1.0;
        x0 = std::max(0, static_cast<int>(std::min(hand.x - reach, ex - er)));
        x1 = std::min(bgr.cols - 1, static_cast<int>(std::max(hand.x + reach, ex + er)) + 1);
        y0 = std::max(0, static_cast<int>(std::min(hand.y - reach, ey - er)));
        y1 = std::min(bgr.rows - 1, static_cast<int>(std::max(hand.y + reach, ey + er)) + 1);
    }
    const double* skin = hand.skin;  // BGR
    for (int y = y0; y <= y1; ++y) {
        auto* row = bgr.ptr<cv::Vec3b>(y);
        for (int x = x0; x <= x1; ++x) {
            // Palm: an ellipse, longer across the hand; distance approximated in palm units.
            const double lx = (x - hand.x) * dx + (y - hand.y) * dy;
            const double ly = (x - hand.x) * px + (y - hand.y) * py;
            double d = (std::hypot(lx / 0.95, ly / 1.05) - r);
            for (const Capsule& c : caps)
                d = std::min(d, segmentDistance(x, y, c.ax, c.ay, c.bx, c.by) - c.radius);
            if (arm)
                d = std::min(d,
                             segmentDistance(x, y, forearm.ax, forearm.ay, forearm.bx, forearm.by) -
                                 forearm.radius);
            const double alpha = std::clamp(0.5 - d, 0.0, 1.0);
            if (alpha <= 0.0)
                continue;
            // Rounded shading: darker towards the outline and towards the wrist.
            const double light = 0.80 + 0.12 * std::clamp(-d / (0.4 * r), 0.0, 1.0) +
                                 0.08 * std::clamp(lx / (2.0 * r), -1.0, 1.0);
            for (int c = 0; c < 3; ++c) {
                const double v = std::min(255.0, skin[c] * light);
                row[x][c] = cv::saturate_cast<std::uint8_t>(row[x][c] + (v - row[x][c]) * alpha);
            }
        }
    }
}

namespace {

cv::Mat composeScene(const cv::Mat& background, const FrameSpec& s, const vision::Quad& quad,
                     const vision::Quad& distractorQuad, const HandPose& hand)
{
    cv::Mat out = background.clone();
    if (s.distractor)
        platform::drawCardQuad(viewOf(out), distractorQuad, s.distractorPaint);
    if (s.backHand)
        drawHand(out, s.backHandPose);
    if (s.card)
        platform::drawCardQuad(viewOf(out), quad, s.paint);
    if (s.hand)
        drawHand(out, hand);
    return out;
}

}  // namespace

cv::Mat renderFrame(const cv::Mat& background, const FrameSpec& spec, std::uint64_t noiseSeed)
{
    cv::Mat scene = composeScene(background, spec, spec.quad, spec.distractorQuad, spec.handPose);
    if (spec.interlace) {
        const cv::Mat previous = composeScene(background, spec, spec.previousQuad,
                                              spec.previousDistractorQuad, spec.previousHandPose);
        for (int y = 1; y < scene.rows; y += 2)
            previous.row(y).copyTo(scene.row(y));
    }
    if (spec.blurSigma > 0.0)
        cv::GaussianBlur(scene, scene, cv::Size(0, 0), spec.blurSigma);
    // Light/gain and sensor noise, then the 8-bit converter saturates (clipping at 255).
    cv::Mat f;
    scene.convertTo(f, CV_32FC3, spec.gain);
    if (spec.noiseSigma > 0.0) {
        cv::Mat noise(f.size(), CV_32FC3);
        cv::RNG rng(noiseSeed * 0x9E3779B97F4A7C15ull + 1);
        rng.fill(noise, cv::RNG::NORMAL, 0.0, spec.noiseSigma);
        f += noise;
    }
    cv::Mat out;
    f.convertTo(out, CV_8UC3);
    return out;
}

vision::Quad trainingQuad(cv::Size size) noexcept
{
    constexpr float kMargin = 8.0f;
    const float r = size.width - 0.5f + kMargin, b = size.height - 0.5f + kMargin;
    const float l = -0.5f - kMargin, t = -0.5f - kMargin;
    return {vision::Point2f{l, t}, vision::Point2f{r, t}, vision::Point2f{r, b},
            vision::Point2f{l, b}};
}

bool quadTouchesImage(const vision::Quad& quad, cv::Size size) noexcept
{
    const auto [minX, minY, maxX, maxY] = vision::extentOf(quad);
    // Separating axes of two convex polygons: the image's axes, then the quad's edge normals.
    const float left = -0.5f, top = -0.5f, right = size.width - 0.5f, bottom = size.height - 0.5f;
    if (maxX <= left || maxY <= top || minX >= right || minY >= bottom)
        return false;
    const float rx[4] = {left, right, right, left}, ry[4] = {top, top, bottom, bottom};
    for (int i = 0; i < 4; ++i) {
        const vision::Point2f a = quad[i], b = quad[(i + 1) % 4];
        bool allOutside = true;  // clockwise on screen (y down): inside is to the right
        for (int k = 0; k < 4 && allOutside; ++k)
            allOutside = (b.x - a.x) * (ry[k] - a.y) - (b.y - a.y) * (rx[k] - a.x) <= 0.0f;
        if (allOutside)
            return false;
    }
    return true;
}

vision::Quad truthCorners(const vision::Quad& quad) noexcept
{
    int first = 0;
    for (int i = 1; i < 4; ++i)
        if (quad[i].x + quad[i].y < quad[first].x + quad[first].y)
            first = i;
    vision::Quad out;
    for (int i = 0; i < 4; ++i)
        out[i] = quad[(first + i) % 4];
    return out;
}

}  // namespace cardgen
