// The synthesized training shapes (§5, 5.3.1): the pose at zero is the fit, yaw and pitch turn the
// head the documented way, the same seed gives the same shapes, the ranges are kept.
#include "shape_synthesis.hpp"

#include "test_paths.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

const std::string kCandide = testing_support::sharedData("candide3/candide3.wfm");

class ShapeSynthesisTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!std::filesystem::exists(kCandide))
            GTEST_SKIP() << kCandide << " not present";
        face = vision::reduceCandideForTracking(aam::loadWfm(kCandide));
        fit.translation = {320, 240};
        fit.a = 150;
        fit.b = 0;
        fit.sigma.assign(face.shapeUnits.size(), 0.1f);
        fit.tau.assign(face.animationUnits.size(), 0.2f);
        nose = static_cast<std::size_t>(face.indexOfCandideVertex(5));
        chin = static_cast<std::size_t>(face.indexOfCandideVertex(10));
    }
    vision::CandideMesh face;
    aam::CandideFit fit;
    std::size_t nose = 0, chin = 0;
};

TEST_F(ShapeSynthesisTest, NoTurnIsTheFitsProjection)
{
    const aam::Shape2d shape = aam::posedShape(face, fit, 0, 0, fit.tau);
    const auto projected = aam::projectedVertices(face, fit);
    ASSERT_EQ(shape.size(), projected.size());
    for (std::size_t v = 0; v < shape.size(); ++v)
        EXPECT_LT((shape[v] - projected[v]).norm(), 1e-9);
}

TEST_F(ShapeSynthesisTest, YawMovesTheNoseRightAndPitchDown)
{
    const aam::Shape2d front = aam::posedShape(face, fit, 0, 0, fit.tau);
    const aam::Shape2d left = aam::posedShape(face, fit, 0.3, 0, fit.tau);
    const aam::Shape2d down = aam::posedShape(face, fit, 0, 0.3, fit.tau);
    // The nose tip stands out of the face more than the chin, so it moves more.
    EXPECT_GT(left[nose].x() - front[nose].x(), left[chin].x() - front[chin].x() + 5);
    EXPECT_GT(down[nose].y() - front[nose].y(), 5);  // about 150 px * 0.05
}

TEST_F(ShapeSynthesisTest, SameSeedSameShapesWithinTheRanges)
{
    aam::SynthesisOptions options;
    const auto a = aam::synthesizeShapes(face, fit, options);
    const auto b = aam::synthesizeShapes(face, fit, options);
    ASSERT_EQ(a.size(), 100u);
    EXPECT_EQ(a[57], b[57]);
    options.seed = 2;
    EXPECT_NE(aam::synthesizeShapes(face, fit, options)[0], a[0]);
    // |yaw| <= 30 degrees bounds how far the nose tip moves from its frontal place: at most
    // k (|x| (1 - cos 30) + |z| sin 30 + the animation units' pull), here well under 30 px.
    const aam::Shape2d front = aam::posedShape(face, fit, 0, 0, fit.tau);
    double widest = 0;
    for (const auto& s : a)
        widest = std::max(widest, std::abs(s[nose].x() - front[nose].x()));
    EXPECT_GT(widest, 10);
    EXPECT_LT(widest, 0.5 * 150 * 0.21 + 1);
}

TEST_F(ShapeSynthesisTest, TheUnitsMustBeTheTrackedSix)
{
    vision::CandideMesh other = face;
    other.animationUnits.pop_back();
    try {
        aam::synthesizeShapes(other, fit);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(),
                     "shape synthesis: the mesh has 5 animation units, the ranges are for 6");
    }
}

}  // namespace
