// headgen: the projection agrees with the model builder's (aam::posedShape), a rendered vertex
// lands where the projection says, the truth file round-trips the pose, the frames are the same
// for the same seed, and a hand hides the vertices under it.
#include "candide_fit.hpp"
#include "head_projection.hpp"
#include "head_renderer.hpp"
#include "head_scene.hpp"
#include "head_truth.hpp"
#include "shape_synthesis.hpp"
#include "test_paths.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <sstream>

namespace {

using testing_support::sharedData;

const std::string kCandide = sharedData("candide3/candide3.wfm");

class HeadgenTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!std::filesystem::exists(kCandide))
            GTEST_SKIP() << kCandide << " not present";
        mesh = vision::reduceCandideForTracking(aam::loadWfm(kCandide));
        sigma.assign(mesh.shapeUnits.size(), 0.f);
        sigma[0] = 0.2f;
        sigma[7] = -0.1f;
        pose.yawDeg = 20, pose.pitchDeg = -8, pose.rollDeg = 12;
        pose.scale = 110, pose.translation = {330, 250};
        pose.animation = {0.5f, 0.2f, -0.3f, 0.1f, 0.f, 0.4f};
    }

    Eigen::Vector2d at(const headgen::ProjectedHead& head, int candide) const
    {
        return head.image[static_cast<std::size_t>(mesh.indexOfCandideVertex(candide))];
    }

    /// A flat grey texture: the frontal, neutral head at 150 px per unit in a 640x480 photograph.
    headgen::HeadTexture flatTexture() const
    {
        headgen::HeadTexture t;
        t.name = "flat";
        t.photo = cv::Mat(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
        headgen::HeadPose2d frontal;
        frontal.scale = 150, frontal.translation = {320, 240};
        t.uv = headgen::projectHead(mesh, sigma, frontal).image;
        t.sigma = sigma;
        return t;
    }

    vision::CandideMesh mesh;
    std::vector<float> sigma;
    headgen::HeadPose2d pose;
};

TEST_F(HeadgenTest, ProjectionIsTheModelBuildersPosedShape)
{
    aam::CandideFit fit;
    fit.translation = pose.translation;
    constexpr double kRad = 3.14159265358979323846 / 180.0;
    fit.a = pose.scale * std::cos(pose.rollDeg * kRad);
    fit.b = pose.scale * std::sin(pose.rollDeg * kRad);
    fit.sigma = sigma;
    const std::vector<float> tau(pose.animation.begin(), pose.animation.end());
    const aam::Shape2d expected =
        aam::posedShape(mesh, fit, pose.yawDeg * kRad, pose.pitchDeg * kRad, tau);
    const headgen::ProjectedHead head = headgen::projectHead(mesh, sigma, pose);
    ASSERT_EQ(head.image.size(), expected.size());
    for (std::size_t v = 0; v < expected.size(); ++v)
        EXPECT_LT((head.image[v] - expected[v]).norm(), 1e-9) << "vertex " << v;
}

TEST_F(HeadgenTest, SignsOfYawRollAndPitchAreTheTruthFilesConventions)
{
    headgen::HeadPose2d p;
    p.scale = 100, p.translation = {320, 240};
    const auto level = headgen::projectHead(mesh, sigma, p);
    p.rollDeg = 10;  // clockwise on screen: the image-right eye corner (the person's left) lower
    const auto rolled = headgen::projectHead(mesh, sigma, p);
    EXPECT_GT(at(rolled, 20).y() - at(rolled, 53).y(), 10.0);
    p.rollDeg = 0, p.yawDeg = 20;  // the nose moves to the image's right
    EXPECT_GT(at(headgen::projectHead(mesh, sigma, p), 5).x() - at(level, 5).x(), 5.0);
    p.yawDeg = 0, p.pitchDeg = 15;  // turned down: the nose tip drops
    EXPECT_GT(at(headgen::projectHead(mesh, sigma, p), 5).y() - at(level, 5).y(), 3.0);
}

TEST_F(HeadgenTest, ARenderedVertexLandsWhereTheProjectionSays)
{
    headgen::HeadTexture texture = flatTexture();
    // A red dot on the left mouth corner and one on the right eye's outer corner in the texture
    // photograph (where every triangle around the vertex faces the camera).
    for (int candide : {31, 53}) {
        const Eigen::Vector2d uv =
            texture.uv[static_cast<std::size_t>(mesh.indexOfCandideVertex(candide))];
        cv::circle(texture.photo, cv::Point2d(uv.x(), uv.y()), 2, cv::Scalar(0, 0, 255), cv::FILLED,
                   cv::LINE_AA);
    }
    const headgen::ProjectedHead head = headgen::projectHead(mesh, sigma, pose);
    cv::Mat frame(480, 640, CV_32FC3, cv::Scalar(0, 255, 0));
    const std::vector<bool> seen = headgen::drawHead(frame, mesh, texture, head);
    for (int candide : {31, 53}) {
        const Eigen::Vector2d expected = at(head, candide);
        EXPECT_TRUE(seen[static_cast<std::size_t>(mesh.indexOfCandideVertex(candide))]);
        // The red dot's centroid near the projected vertex.
        const cv::Rect window(static_cast<int>(expected.x()) - 12,
                              static_cast<int>(expected.y()) - 12, 25, 25);
        cv::Mat red;
        cv::inRange(frame(window), cv::Scalar(0, 0, 150), cv::Scalar(100, 100, 255), red);
        const cv::Moments m = cv::moments(red, true);
        ASSERT_GT(m.m00, 4.0) << "no dot near vertex " << candide;
        const Eigen::Vector2d found(window.x + m.m10 / m.m00, window.y + m.m01 / m.m00);
        EXPECT_LT((found - expected).norm(), 1.0) << "vertex " << candide;
    }
}

TEST_F(HeadgenTest, ATurnedHeadHidesTheFarSideOfTheNose)
{
    const headgen::HeadTexture texture = flatTexture();
    pose.yawDeg = 30, pose.pitchDeg = 0, pose.rollDeg = 0;
    const headgen::ProjectedHead head = headgen::projectHead(mesh, sigma, pose);
    cv::Mat frame(480, 640, CV_32FC3, cv::Scalar(0, 0, 0));
    const std::vector<bool> seen = headgen::drawHead(frame, mesh, texture, head);
    const auto seenAt = [&](int c) {
        return seen[static_cast<std::size_t>(mesh.indexOfCandideVertex(c))];
    };
    // Turned to its left, the face shows its right side: the nose's right border (CANDIDE 58)
    // stays in view, its left border (25) goes behind the nose.
    EXPECT_TRUE(seenAt(58));
    EXPECT_FALSE(seenAt(25));
    EXPECT_TRUE(seenAt(5));
    EXPECT_TRUE(seenAt(20));
}

TEST_F(HeadgenTest, TruthFileRoundTripsThePoseAndVertices)
{
    headgen::HeadTruth truth;
    truth.source = "04-1m";
    truth.pose = pose;
    truth.box = {10, 20, 300, 400};
    truth.hand = {true, {200, 300}, 80, -15};
    const headgen::ProjectedHead head = headgen::projectHead(mesh, sigma, pose);
    for (std::size_t v = 0; v < head.image.size(); ++v)
        truth.vertices.push_back({mesh.candideNumber[v], head.image[v], v % 3 != 0});
    std::stringstream file;
    headgen::writeHeadTruth(file, truth);
    const headgen::HeadTruth back = headgen::readHeadTruth(file, "t.txt");
    EXPECT_EQ(back.source, "04-1m");
    EXPECT_NEAR(back.pose.yawDeg, pose.yawDeg, 1e-4);
    EXPECT_NEAR(back.pose.pitchDeg, pose.pitchDeg, 1e-4);
    EXPECT_NEAR(back.pose.rollDeg, pose.rollDeg, 1e-4);
    EXPECT_NEAR(back.pose.scale, pose.scale, 1e-4);
    EXPECT_LT((back.pose.translation - pose.translation).norm(), 1e-4);
    for (std::size_t j = 0; j < pose.animation.size(); ++j)
        EXPECT_NEAR(back.pose.animation[j], pose.animation[j], 1e-4);
    EXPECT_TRUE(back.hand.present);
    ASSERT_EQ(back.vertices.size(), truth.vertices.size());
    // The pose read back projects onto the vertices written.
    const headgen::ProjectedHead again = headgen::projectHead(mesh, sigma, back.pose);
    for (std::size_t v = 0; v < back.vertices.size(); ++v) {
        EXPECT_LT((back.vertices[v].image - again.image[v]).norm(), 1e-3);
        EXPECT_EQ(back.vertices[v].seen, truth.vertices[v].seen);
        EXPECT_EQ(back.vertices[v].candide, truth.vertices[v].candide);
    }
}

TEST(HeadTruthFile, AMalformedLineIsOneLineNamingIt)
{
    std::istringstream file("source x\npose 1 2 3\n");
    try {
        headgen::readHeadTruth(file, "t.txt");
        FAIL() << "accepted a short pose line";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "t.txt:2: pose: expected 6 numbers");
    }
}

TEST(HeadScene, TheSameSeedGivesTheSameFramesAndAHandHidesVertices)
{
    if (!std::filesystem::exists(sharedData("imm_face_db/04-1m.asf")) ||
        !std::filesystem::exists(kCandide))
        GTEST_SKIP() << "shared data not present";
    headgen::SceneOptions o;
    o.dataDir = sharedData("");
    o.motion.frames = 3;
    o.motion.seed = 5;
    o.motion.size = {320, 240};
    o.motion.hand = headgen::HandMode::Some;
    o.motion.sequence = false;
    o.faces = {sharedData("imm_face_db/04-1m.asf"), sharedData("imm_face_db/08-1f.asf")};
    const headgen::HeadScene a(o), b(o);
    for (int i = 0; i < 2; ++i) {
        const auto fa = a.frame(i), fb = b.frame(i);
        EXPECT_EQ(cv::norm(fa.bgr, fb.bgr, cv::NORM_INF), 0.0) << "frame " << i;
        EXPECT_EQ(fa.truth.pose.yawDeg, fb.truth.pose.yawDeg);
    }
    // Frame 1 has the hand (every other frame): some vertex the head shows is under it.
    const auto noHand = a.frame(0), hand = a.frame(1);
    EXPECT_FALSE(noHand.truth.hand.present);
    ASSERT_TRUE(hand.truth.hand.present);
    const auto seen = [](const headgen::HeadTruth& t) {
        return std::count_if(t.vertices.begin(), t.vertices.end(), [](auto& v) { return v.seen; });
    };
    EXPECT_GT(seen(noHand.truth), 60);
    o.motion.hand = headgen::HandMode::None;
    const headgen::HeadScene without(o);
    EXPECT_LT(seen(hand.truth), seen(without.frame(1).truth));
}

}  // namespace
