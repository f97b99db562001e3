// Mirrored training images (§5, 5.3.1): every tracked vertex has a mirror partner, partners pair
// both ways, the inner lips pair upper with upper, and a posed head's shape mirrored is the
// mirrored head's (yaw negated) with every vertex in its partner's place.
#include "mirrored_training.hpp"

#include "test_paths.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

const std::string kCandide = testing_support::sharedData("candide3/candide3.wfm");

class MirroredTrainingTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!std::filesystem::exists(kCandide))
            GTEST_SKIP() << kCandide << " not present";
        face = vision::reduceCandideForTracking(aam::loadWfm(kCandide));
    }
    vision::CandideMesh face;
};

TEST_F(MirroredTrainingTest, PartnersPairBothWaysAndLipsWithTheirOwnLip)
{
    const std::vector<int> partners = aam::mirrorPartners(face);
    ASSERT_EQ(partners.size(), face.vertices.size());
    for (std::size_t v = 0; v < partners.size(); ++v)
        EXPECT_EQ(partners[static_cast<std::size_t>(partners[v])], static_cast<int>(v));
    // 81/82 (upper inner lip) and 83/84 (lower) share places at rest; the jaw tells them apart.
    const auto partnerOf = [&](int number) {
        return face.candideNumber[static_cast<std::size_t>(
            partners[static_cast<std::size_t>(face.indexOfCandideVertex(number))])];
    };
    EXPECT_EQ(partnerOf(81), 82);
    EXPECT_EQ(partnerOf(83), 84);
}

TEST_F(MirroredTrainingTest, AMirroredTurnedHeadIsTheHeadTurnedTheOtherWay)
{
    aam::CandideFit fit;
    fit.translation = {319.5, 240};  // the middle of a 640-px image: the mirror keeps it there
    fit.a = 150;
    fit.b = 0;
    fit.sigma.assign(face.shapeUnits.size(), 0.f);
    fit.tau.assign(face.animationUnits.size(), 0.f);
    fit.tau[0] = 0.5f;  // jaw open: the lips apart
    const aam::Shape2d left = aam::posedShape(face, fit, 0.3, 0.1, fit.tau);
    const aam::Shape2d right = aam::posedShape(face, fit, -0.3, 0.1, fit.tau);
    const aam::Shape2d mirrored = aam::mirroredShape(left, aam::mirrorPartners(face), 640);
    for (std::size_t v = 0; v < right.size(); ++v)
        EXPECT_LT((mirrored[v] - right[v]).norm(), 1e-3) << "vertex " << face.candideNumber[v];
}

}  // namespace
