// Roll by point symmetry (METHOD.md §4) on the IMM frontal faces rotated under mirror-eval's
// `mirror-eval roll` protocol (imm_rotated_faces.hpp). Corners: cv::goodFeaturesToTrack in the
// face box (a stand-in for our own Shi-Tomasi): at most 60 (and, second, 40) corners, none closer
// than 1/20 of the box side. Also scored: the dissertation's own variant (whole degrees, plain
// mean, axis through the box centre), its least-squares line-fit baseline, and "upright".

#include "imm_rotated_faces.hpp"
#include "vision/roll_estimator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace imm_rotated_faces;

/// Every configuration on one set of face boxes.
struct Results {
    Errors symmetry60{"symmetry (60 corners)", {}};
    Errors symmetry40{"symmetry (40 corners)", {}};
    Errors dissertation60{"dissertation's symmetry (60 corners)", {}};
    Errors lineFit60{"line-fit baseline (60 corners)", {}};
    Errors upright{"assume vertical", {}};
    void report(const char* boxes) const
    {
        for (const Errors* e : {&symmetry60, &symmetry40, &dissertation60, &lineFit60, &upright})
            printErrors(*e, boxes);
    }
};

/// Corners as the face pipeline will find them: Shi-Tomasi in the box, at most `count`, no two
/// closer than 1/20 of the box side.
std::vector<Point2f> corners(const cv::Mat& gray, cv::Rect box, int count)
{
    std::vector<cv::Point2f> found;
    cv::goodFeaturesToTrack(gray(box), found, count, 0.01, box.width / 20.0);
    std::vector<Point2f> points;
    for (const auto& c : found)
        points.push_back({c.x + static_cast<float>(box.x), c.y + static_cast<float>(box.y)});
    return points;
}

void estimate(const cv::Mat& gray, cv::Rect box, double truth, Results& results)
{
    box &= cv::Rect(0, 0, gray.cols, gray.rows);
    const Point2f centre{static_cast<float>(box.x) + 0.5f * static_cast<float>(box.width - 1),
                         static_cast<float>(box.y) + 0.5f * static_cast<float>(box.height - 1)};
    const auto size = static_cast<float>(box.width);
    // The dissertation's method: whole degrees, plain mean, axis through the box centre.
    vision::RollEstimatorOptions plain;
    plain.refineToleranceDegrees = 0.f;
    plain.trimFraction = 0.f;
    plain.capFraction = 0.f;
    plain.maxAxisOffsetFraction = 0.f;

    const auto points60 = corners(gray, box, 60);
    const auto points40 = corners(gray, box, 40);
    auto error = [&](const vision::RollEstimate& e) { return std::fabs(e.rollDegrees - truth); };
    results.symmetry60.values.push_back(
        error(vision::estimateRollBySymmetry(points60, centre, size)));
    results.symmetry40.values.push_back(
        error(vision::estimateRollBySymmetry(points40, centre, size)));
    results.dissertation60.values.push_back(
        error(vision::estimateRollBySymmetry(points60, centre, size, plain)));
    results.lineFit60.values.push_back(error(vision::estimateRollByLineFit(points60)));
    results.upright.values.push_back(std::fabs(truth));
}

TEST(RollLandmarksPeer, ImmFrontalFacesRotatedUpTo30Degrees)
{
    const auto samples = rotatedSamples(2006u, false);
    ASSERT_EQ(samples.size(), 80u) << "IMM frontal faces (types 1 and 2) not found";
    Results detected, fromLandmarks;
    int missed = 0;
    for (const Sample& s : samples) {
        // Our positive roll is clockwise on screen, as the crop was turned.
        EXPECT_NEAR(s.truth, s.uprightTruth + s.rotation, 1e-3);
        // (a) the cascade's box holding the eye midpoint and mouth centre, if it finds one.
        if (s.detected)
            estimate(s.crop, s.cascadeBox, s.truth, detected);
        else
            ++missed;
        // (b) every face: a square of 2.2x the eye-mouth distance about the face centre, off by up
        // to 5% of its size each way as a detector's box would be.
        estimate(s.crop, s.landmarkBox, s.truth, fromLandmarks);
    }
    std::printf("roll: cascade missed %d of %zu rotated faces\n", missed, samples.size());
    detected.report("cascade-box");
    fromLandmarks.report("landmark-box");

    // The product's targets (mean <= 4.0 degrees, >= 85% within 5; the dissertation had 6.0 and 73%),
    // on the faces the cascade finds and on every face with a jittered box.
    ASSERT_GE(detected.symmetry60.values.size(), 55u);
    for (const Results* r : {&detected, &fromLandmarks}) {
        EXPECT_LE(r->symmetry60.mean(), 3.5);
        EXPECT_GE(r->symmetry60.within(5.0), 0.88);
        EXPECT_LE(r->symmetry40.mean(), 5.0);
        EXPECT_GE(r->symmetry40.within(5.0), 0.85);
        // Better than the dissertation's own scoring on the same corners, and far better than the
        // line fit it compared with.
        EXPECT_LT(r->symmetry60.mean(), r->dissertation60.mean());
        EXPECT_LT(r->symmetry60.mean() * 3.0, r->lineFit60.mean());
    }
}

}  // namespace
