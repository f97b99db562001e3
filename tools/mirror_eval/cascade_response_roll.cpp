#include "cascade_response_roll.hpp"

#include "vision/upright_patch.hpp"

#include <array>

namespace mirror_eval {

namespace {

constexpr int kPatch = 48;  // the face box becomes ~30 px: the 24 px window fits at a few scales
constexpr float kSquarePerBox = 1.6f;
constexpr double kRange = 55.0;  // beyond the +-30 rotation plus the faces' own roll
constexpr double kStep = 2.5;
constexpr int kAngles = static_cast<int>(2.0 * kRange / kStep) + 1;
constexpr double kRunFraction = 0.3;

vision::FaceDetectorOptions patchDetectorOptions()
{
    vision::FaceDetectorOptions o;
    o.maxFrameSize = {kPatch, kPatch};
    o.scaleFactor = 1.05;
    o.minNeighbors = 0;
    return o;
}

}  // namespace

CascadeResponseRoll::CascadeResponseRoll(const vision::HaarCascade& cascade)
    : detector_(cascade, patchDetectorOptions()), patch_(kPatch, kPatch, vision::PixelFormat::Gray8)
{
}

double CascadeResponseRoll::estimate(const vision::ConstImageView& gray, vision::Point2f centre,
                                     float boxSize)
{
    std::array<double, kAngles> hits{};
    int peak = 0;
    for (int k = 0; k < kAngles; ++k) {
        vision::ImageView p = patch_.view();
        if (!vision::warpUpright(gray, centre, static_cast<float>(-kRange + kStep * k),
                                 kSquarePerBox * boxSize, p))
            continue;
        if (detector_.detect(vision::ConstImageView{p.data, p.width, p.height, p.stride,
                                                    vision::PixelFormat::Gray8}) < 0)
            continue;
        hits[static_cast<std::size_t>(k)] = static_cast<double>(detector_.rawHits().size());
        if (hits[static_cast<std::size_t>(k)] > hits[static_cast<std::size_t>(peak)])
            peak = k;
    }
    const double floor = kRunFraction * hits[static_cast<std::size_t>(peak)];
    if (!(floor > 0.0))
        return 0.0;
    int lo = peak, hi = peak;
    while (lo > 0 && hits[static_cast<std::size_t>(lo - 1)] > floor)
        --lo;
    while (hi + 1 < kAngles && hits[static_cast<std::size_t>(hi + 1)] > floor)
        ++hi;
    double weight = 0.0, sum = 0.0;
    for (int k = lo; k <= hi; ++k) {
        weight += hits[static_cast<std::size_t>(k)];
        sum += hits[static_cast<std::size_t>(k)] * (-kRange + kStep * k);
    }
    return sum / weight;
}

}  // namespace mirror_eval
