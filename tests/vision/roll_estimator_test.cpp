// Roll by point symmetry on synthetic face-like corner sets: known rotations are recovered to
// sub-degree accuracy, asymmetric outliers and an off-centre box are tolerated, degenerate input
// has no confidence, and the line-fit baseline folds its slope into +-45 degrees.

#include "vision/roll_estimator.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using vision::Point2f;

constexpr float kPi = 3.14159265358979f;
constexpr float kBox = 100.f;
const Point2f kCentre{160.f, 120.f};

/// Deterministic uniform noise in [-1, 1) on every platform (std distributions are not).
struct Lcg {
    std::uint32_t state;
    float next()
    {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / static_cast<float>(1u << 23) - 1.f;
    }
};

/// Corners of an upright face in a 100-pixel box, relative to its centre (x right, y down):
/// eye corners, brow ends, nostrils, mouth corners and lip centre, jaw, chin, nose bridge.
std::vector<Point2f> uprightFace()
{
    std::vector<Point2f> half = {
        {-32.f, -12.f}, {-14.f, -12.f}, {-23.f, -15.f},  // eye corners and lid
        {-36.f, -24.f}, {-10.f, -25.f},                  // brow ends
        {-6.f, 12.f},                                    // nostril
        {-17.f, 27.f},                                   // mouth corner
        {-44.f, 10.f},  {-38.f, 34.f},                   // jaw
    };
    std::vector<Point2f> points;
    for (Point2f p : half) {
        points.push_back(p);
        points.push_back({-p.x, p.y});
    }
    points.push_back({0.f, 24.f});  // upper lip centre
    points.push_back({0.f, 31.f});  // lower lip
    points.push_back({0.f, 45.f});  // chin
    points.push_back({0.f, -8.f});  // nose bridge
    return points;
}

/// The face rotated by `degrees` (positive: clockwise on screen) about kCentre, with noise.
std::vector<Point2f> observed(const std::vector<Point2f>& upright, float degrees, float noise,
                              std::uint32_t seed)
{
    Lcg rng{seed};
    const float a = degrees * kPi / 180.f, c = std::cos(a), s = std::sin(a);
    std::vector<Point2f> points;
    for (Point2f p : upright)
        points.push_back({kCentre.x + c * p.x - s * p.y + noise * rng.next(),
                          kCentre.y + s * p.x + c * p.y + noise * rng.next()});
    return points;
}

TEST(RollEstimator, RecoversKnownRotationsOfASymmetricFace)
{
    const auto face = uprightFace();
    for (float degrees = -30.f; degrees <= 30.f; degrees += 2.7f) {
        const auto points = observed(face, degrees, 0.f, 1);
        const auto roll = vision::estimateRollBySymmetry(points, kCentre, kBox);
        EXPECT_NEAR(roll.rollDegrees, degrees, 0.1f) << "true roll " << degrees;
        EXPECT_GT(roll.confidence, 0.8f);
        EXPECT_NEAR(roll.symmetryDistance, 0.f, 0.01f);
        EXPECT_EQ(roll.points, static_cast<int>(face.size()));
    }
}

TEST(RollEstimator, SubDegreeRefinementBeatsTheWholeDegreeScan)
{
    const auto points = observed(uprightFace(), 12.4f, 0.f, 1);
    vision::RollEstimatorOptions whole;
    whole.refineToleranceDegrees = 0.f;
    EXPECT_FLOAT_EQ(vision::estimateRollBySymmetry(points, kCentre, kBox, whole).rollDegrees, 12.f);
    EXPECT_NEAR(vision::estimateRollBySymmetry(points, kCentre, kBox).rollDegrees, 12.4f, 0.05f);
}

TEST(RollEstimator, NoisyFaceWithAsymmetricOutliersWithinHalfADegree)
{
    const auto face = uprightFace();
    double sumError = 0.0;
    int n = 0;
    for (float degrees = -30.f; degrees <= 30.f; degrees += 3.3f) {
        auto upright = face;
        // Hair on one side, a collar corner, a background corner: no mirror partner.
        upright.push_back({-30.f, -46.f});
        upright.push_back({-20.f, -48.f});
        upright.push_back({38.f, 49.f});
        upright.push_back({47.f, -40.f});
        const auto points = observed(upright, degrees, 0.8f, 7u + static_cast<std::uint32_t>(n));
        const auto roll = vision::estimateRollBySymmetry(points, kCentre, kBox);
        EXPECT_NEAR(roll.rollDegrees, degrees, 0.5f) << "true roll " << degrees;
        EXPECT_GT(roll.confidence, 0.4f);
        sumError += std::fabs(roll.rollDegrees - degrees);
        ++n;
    }
    EXPECT_LT(sumError / n, 0.3);
}

TEST(RollEstimator, ToleratesABoxCentreOffTheFaceAxis)
{
    // A detector box 4 px (4% of its size) to the side of the face's axis.
    const auto points = observed(uprightFace(), -17.f, 0.5f, 3);
    const Point2f shifted{kCentre.x + 4.f, kCentre.y - 2.f};
    const auto roll = vision::estimateRollBySymmetry(points, shifted, kBox);
    EXPECT_NEAR(roll.rollDegrees, -17.f, 0.5f);
}

TEST(RollEstimator, DegenerateInputHasNoConfidence)
{
    const std::vector<Point2f> none;
    const std::vector<Point2f> one = {{10.f, 10.f}};
    const std::vector<Point2f> two = {{10.f, 10.f}, {30.f, 12.f}};
    for (const auto* points : {&none, &one, &two}) {
        const auto roll = vision::estimateRollBySymmetry(*points, {20.f, 10.f}, kBox);
        EXPECT_EQ(roll.confidence, 0.f) << points->size() << " points";
        EXPECT_EQ(roll.rollDegrees, 0.f);
    }
    // Every point on the centre: every angle scores alike.
    const std::vector<Point2f> stacked(5, kCentre);
    EXPECT_EQ(vision::estimateRollBySymmetry(stacked, kCentre, kBox).confidence, 0.f);
    // No box.
    EXPECT_EQ(vision::estimateRollBySymmetry(uprightFace(), kCentre, 0.f).confidence, 0.f);
}

TEST(RollEstimator, ScatteredPointsAreLessConfidentThanAFace)
{
    Lcg rng{42};
    std::vector<Point2f> scattered;
    for (int i = 0; i < 22; ++i)
        scattered.push_back({kCentre.x + 45.f * rng.next(), kCentre.y + 45.f * rng.next()});
    const auto face = observed(uprightFace(), 8.f, 0.8f, 5);
    EXPECT_LT(vision::estimateRollBySymmetry(scattered, kCentre, kBox).confidence,
              vision::estimateRollBySymmetry(face, kCentre, kBox).confidence);
}

TEST(RollEstimator, IgnoresPointsBeyondCapacityAndDoesNotAllocate)
{
    // Whole copies of the face, then centre points (on every axis), up to capacity; then points
    // that would ruin the symmetry if they were read.
    const auto face = observed(uprightFace(), 5.f, 0.f, 1);
    std::vector<Point2f> points;
    while (points.size() + face.size() <= vision::kMaxRollPoints)
        points.insert(points.end(), face.begin(), face.end());
    points.resize(vision::kMaxRollPoints, kCentre);
    for (int i = 0; i < 10; ++i)
        points.push_back({kCentre.x - 40.f, kCentre.y + 3.f * i});

    vision::RollEstimate roll;
    if (testing_support::allocationCountingAvailable()) {
        testing_support::AllocationScope scope;
        roll = vision::estimateRollBySymmetry(points, kCentre, kBox);
        EXPECT_EQ(scope.counts().cxxNew, 0);
        EXPECT_EQ(scope.counts().ownMalloc, 0);
    } else {
        roll = vision::estimateRollBySymmetry(points, kCentre, kBox);
    }
    EXPECT_EQ(roll.points, vision::kMaxRollPoints);
    EXPECT_NEAR(roll.rollDegrees, 5.f, 0.2f);
}

TEST(RollEstimator, SymmetryDistanceIsZeroOnlyAtTheTrueAxis)
{
    const auto points = observed(uprightFace(), 10.f, 0.f, 1);
    EXPECT_NEAR(vision::symmetryDistance(points, kCentre, 10.f, 0.f, 0.f, 0.f), 0.f, 1e-3f);
    EXPECT_GT(vision::symmetryDistance(points, kCentre, 0.f, 0.f, 0.f, 0.f), 1.f);
    // An axis shifted sideways by 3 px matches the face shifted by 3 px along the upright x.
    const float a = 10.f * kPi / 180.f;
    std::vector<Point2f> moved;
    for (Point2f p : points)
        moved.push_back({p.x + 3.f * std::cos(a), p.y + 3.f * std::sin(a)});
    EXPECT_NEAR(vision::symmetryDistance(moved, kCentre, 10.f, 3.f, 0.f, 0.f), 0.f, 1e-3f);
}

TEST(RollEstimator, LineFitBaselineFoldsIntoPlusMinus45)
{
    auto line = [](float degrees) {
        const float a = degrees * kPi / 180.f;
        std::vector<Point2f> points;
        for (int i = -5; i <= 5; ++i)
            points.push_back({50.f + 8.f * i * std::cos(a), 40.f + 8.f * i * std::sin(a)});
        return points;
    };
    EXPECT_NEAR(vision::estimateRollByLineFit(line(20.f)).rollDegrees, 20.f, 1e-3f);
    EXPECT_NEAR(vision::estimateRollByLineFit(line(-35.f)).rollDegrees, -35.f, 1e-3f);
    EXPECT_NEAR(vision::estimateRollByLineFit(line(70.f)).rollDegrees, -20.f, 1e-3f);
    EXPECT_NEAR(vision::estimateRollByLineFit(line(100.f)).rollDegrees, 10.f, 1e-3f);
    EXPECT_NEAR(vision::estimateRollByLineFit(line(20.f)).confidence, 1.f, 1e-4f);
    const std::vector<Point2f> one = {{1.f, 2.f}};
    EXPECT_EQ(vision::estimateRollByLineFit(one).confidence, 0.f);
    const std::vector<Point2f> same(4, Point2f{3.f, 3.f});
    EXPECT_EQ(vision::estimateRollByLineFit(same).confidence, 0.f);
}

}  // namespace
