// CascadeResponseRoll on a real face: it follows a known rotation of the image to 2 degrees (the
// property the truth-noise estimate relies on), and a flat image gives 0.

#include "cascade_response_roll.hpp"

#include "detect_eval.hpp"
#include "face_match.hpp"
#include "face_truth.hpp"
#include "test_paths.hpp"
#include "vision/haar_cascade.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace {

using namespace mirror_eval;

vision::ConstImageView viewOf(const cv::Mat& m)
{
    return {m.data, m.cols, m.rows, static_cast<int>(m.step), vision::PixelFormat::Gray8};
}

TEST(CascadeResponseRoll, FollowsARotationOfTheFace)
{
    const std::string fgnet = testing_support::sharedData("fgnet_talking_face");
    const cv::Mat frame = cv::imread(fgnet + "/images/franck_00000.jpg", cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(frame.empty());
    const std::vector<vision::Point2f> points = loadPts(fgnet + "/points/franck_00000.pts");
    const BoxF box = boundingBox(points);
    const vision::Point2f centre{box.x + 0.5f * box.width, box.y + 0.5f * box.height};
    const float side = std::max(box.width, box.height);

    CascadeResponseRoll roll(vision::loadHaarCascade(kDefaultCascade));
    const double upright = roll.estimate(viewOf(frame), centre, side);
    EXPECT_LT(std::abs(upright), 8.0);  // the head is a little tilted in this frame
    for (const double turn : {-20.0, 15.0}) {
        // OpenCV's positive angle is anticlockwise on screen; roll is clockwise.
        const cv::Mat m = cv::getRotationMatrix2D(cv::Point2f(centre.x, centre.y), -turn, 1.0);
        cv::Mat turned;
        cv::warpAffine(frame, turned, m, frame.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        EXPECT_NEAR(roll.estimate(viewOf(turned), centre, side) - upright, turn, 2.0) << turn;
    }
}

TEST(CascadeResponseRoll, NoHitsGiveZero)
{
    const cv::Mat flat(120, 120, CV_8UC1, cv::Scalar(128));
    CascadeResponseRoll roll(vision::loadHaarCascade(kDefaultCascade));
    EXPECT_EQ(roll.estimate(viewOf(flat), {60.f, 60.f}, 60.f), 0.0);
}

}  // namespace
