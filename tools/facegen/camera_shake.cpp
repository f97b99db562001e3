#include "camera_shake.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace facegen {

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kFramesPerSecond = 30.0;

/// The turn and shift as a 2x3 matrix mapping scene pixels to shaken frame pixels.
cv::Matx23d shakeMatrix(const CameraShake& s, cv::Size size) noexcept
{
    const double r = s.rollDeg * kTwoPi / 360.0;
    const double c = std::cos(r), n = std::sin(r);
    const double xc = 0.5 * (size.width - 1), yc = 0.5 * (size.height - 1);
    // x' = c (x - xc) - n (y - yc) + xc + dx; y' = n (x - xc) + c (y - yc) + yc + dy: with y
    // down, a positive angle turns clockwise on screen, as rolls do.
    return {c, -n, xc - c * xc + n * yc + s.dx, n, c, yc - n * xc - c * yc + s.dy};
}

}  // namespace

CameraShake shakeAt(std::uint32_t seed, int index, double amplitudePx) noexcept
{
    CameraShake s;
    if (amplitudePx <= 0)
        return s;
    Random rng(0x5a4e0000ull + seed);
    const double t = index / kFramesPerSecond;
    double axis[3] = {0, 0, 0};  // dx, dy, roll in units of the amplitude
    for (double& a : axis) {
        for (int k = 0; k < 3; ++k) {
            const double f = rng.uniform(1.5, 7.0), p = rng.uniform(0, kTwoPi);
            a += std::sin(kTwoPi * f * t + p) / 3.0;
        }
    }
    // A jolt of its own each frame (splitmix on the frame index keeps it repeatable).
    Random jolt(0x701e0000ull + seed * 1000003ull + static_cast<std::uint64_t>(index));
    for (double& a : axis)
        a = 0.75 * a + 0.25 * jolt.uniform(-1, 1);
    s.dx = amplitudePx * axis[0];
    s.dy = amplitudePx * axis[1];
    s.rollDeg = kShakeRollPerPixel * amplitudePx * axis[2];
    return s;
}

void applyShake(cv::Mat& frame, const CameraShake& shake)
{
    if (shake.dx == 0 && shake.dy == 0 && shake.rollDeg == 0)
        return;
    cv::Mat out;
    cv::warpAffine(frame, out, cv::Mat(shakeMatrix(shake, frame.size())), frame.size(),
                   cv::INTER_LINEAR, cv::BORDER_REFLECT101);
    frame = out;
}

FaceState shaken(FaceState face, const CameraShake& shake, cv::Size frameSize) noexcept
{
    const cv::Matx23d m = shakeMatrix(shake, frameSize);
    const double x = face.cx, y = face.cy;
    face.cx = m(0, 0) * x + m(0, 1) * y + m(0, 2);
    face.cy = m(1, 0) * x + m(1, 1) * y + m(1, 2);
    face.rollDeg += shake.rollDeg;
    return face;
}

}  // namespace facegen
