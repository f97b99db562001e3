// The per-image CANDIDE fit (§5, eq. 44): known parameters recovered from a synthetic projection,
// the similarity and the whole mesh recovered from a scheme's points alone, the residual on real
// annotations reported and bounded, too few points refused with one line.
#include "candide_fit.hpp"

#include "test_paths.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace {

using testing_support::sharedData;

const std::string kCandide = sharedData("candide3/candide3.wfm");

class CandideFitTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!std::filesystem::exists(kCandide))
            GTEST_SKIP() << kCandide << " not present";
        face = vision::reduceCandideForTracking(aam::loadWfm(kCandide));
        truth.translation = {320, 250};
        truth.a = 150 * std::cos(0.1);  // k = 150 px per model unit, roll 0.1 rad
        truth.b = 150 * std::sin(0.1);
        truth.sigma = {0.3f, -0.2f, 0.1f, 0.2f, -0.3f, 0.25f, -0.15f, 0.2f, 0.05f, -0.2f};
        truth.tau = {0.4f, 0.2f, -0.3f, 0.3f, 0.2f, -0.2f};
    }

    std::vector<aam::MarkedPoint> projectedAt(const std::vector<int>& vertices) const
    {
        const auto projected = aam::projectedVertices(face, truth);
        std::vector<aam::MarkedPoint> marked;
        for (int v : vertices)
            marked.push_back({v, projected[static_cast<std::size_t>(v)]});
        return marked;
    }

    vision::CandideMesh face;
    aam::CandideFit truth;
};

TEST_F(CandideFitTest, RecoversKnownParametersFromEveryVertex)
{
    // Without the prior the fit is exact; with it (the default) the small units shrink a little.
    std::vector<int> all(face.vertices.size());
    for (std::size_t v = 0; v < all.size(); ++v)
        all[v] = static_cast<int>(v);
    aam::CandideFitOptions exact;
    exact.priorWeight = 0;
    const aam::CandideFit fit = aam::fitCandide(face, projectedAt(all), exact);
    EXPECT_NEAR(fit.scale(), 150, 0.1);
    EXPECT_NEAR(fit.rollRadians(), 0.1, 1e-3);
    EXPECT_NEAR(fit.translation.x(), 320, 0.1);
    EXPECT_NEAR(fit.translation.y(), 250, 0.1);
    for (std::size_t j = 0; j < truth.sigma.size(); ++j)
        EXPECT_NEAR(fit.sigma[j], truth.sigma[j], 0.01) << face.shapeUnits[j].name;
    for (std::size_t j = 0; j < truth.tau.size(); ++j)
        EXPECT_NEAR(fit.tau[j], truth.tau[j], 0.01) << face.animationUnits[j].name;
    EXPECT_LT(fit.rmsResidualPx, 0.05);
    const aam::CandideFit prior = aam::fitCandide(face, projectedAt(all));
    for (std::size_t j = 0; j < truth.tau.size(); ++j)
        EXPECT_NEAR(prior.tau[j], truth.tau[j], 0.03) << face.animationUnits[j].name;
}

TEST_F(CandideFitTest, RecoversTheMeshFromTheImmPointsAlone)
{
    // 33 marked vertices cannot pin every unit apart, but the similarity and the mesh they imply
    // must come back.
    std::vector<int> marked;
    for (const aam::SchemeRow& row : aam::immScheme().rows)
        marked.push_back(face.indexOfCandideVertex(row.candideVertex));
    const aam::CandideFit fit = aam::fitCandide(face, projectedAt(marked));
    EXPECT_NEAR(fit.scale(), 150, 1.5);
    EXPECT_NEAR(fit.rollRadians(), 0.1, 0.005);
    const auto expected = aam::projectedVertices(face, truth);
    const auto got = aam::projectedVertices(face, fit);
    double worst = 0;
    for (std::size_t v = 0; v < got.size(); ++v)
        worst = std::max(worst, (got[v] - expected[v]).norm());
    EXPECT_LT(fit.rmsResidualPx, 0.5);
    EXPECT_LT(worst, 3.0);  // px, on a face 150 px per model unit (about 250 px eye to chin)
}

TEST_F(CandideFitTest, RealImmFrontalFacesFitWithinAFewPixels)
{
    // Every IMM person's frontal neutral photograph (type 1): the residual of the 5.3.1 fit.
    if (!std::filesystem::exists(sharedData("imm_face_db")))
        GTEST_SKIP() << "IMM not present";
    double sum = 0;
    double worst = 0;
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(sharedData("imm_face_db"))) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() != ".asf" || name.substr(3, 1) != "1")
            continue;
        const auto marked =
            aam::markedPoints(aam::immScheme(), aam::loadAsf(entry.path().string()), face);
        const aam::CandideFit fit = aam::fitCandide(face, marked);
        sum += fit.rmsResidualPx;
        worst = std::max(worst, fit.rmsResidualPx);
        ++files;
    }
    ASSERT_EQ(files, 40);
    std::printf("IMM type 1: %d photographs, residual rms mean %.2f px, worst %.2f px\n", files,
                sum / files, worst);
    EXPECT_LT(sum / files, 5.0);
    EXPECT_LT(worst, 8.0);
}

TEST_F(CandideFitTest, TooFewPointsAreOneLine)
{
    try {
        aam::fitCandide(face, projectedAt({0, 1, 2}));
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "CANDIDE fit: 3 marked points for 20 unknowns (need at least 10)");
    }
}

}  // namespace
