// The whole model on real data (§5, 5.3.1), leave-persons-out: built from 30 IMM persons, written
// and read back as the runtime will, evaluated on the 10 others, whose faces its shape and
// appearance modes must reconstruct far better than the means alone; a person it saw is refused
// unless the evaluation is labelled person-specific. Skips when the IMM data is absent.
#include "model_building.hpp"
#include "model_evaluation.hpp"
#include "test_paths.hpp"
#include "vision/aam_model.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace {

using testing_support::sharedData;

bool heldOutPerson(int person)
{
    return person % 4 == 0;
}  // 04, 08, ..., 40: the evaluation set

/// IMM image `kind` (1: frontal neutral, 2: happy) of each person in or out of the held-out set.
std::vector<std::string> immFiles(bool heldOut, int kind)
{
    std::vector<std::string> files;
    for (int person = 1; person <= 40; ++person) {
        if (heldOutPerson(person) != heldOut)
            continue;
        char stem[16];
        for (const char sex : {'m', 'f'}) {
            std::snprintf(stem, sizeof stem, "%02d-%d%c.asf", person, kind, sex);
            const std::string path = sharedData(std::string("imm_face_db/") + stem);
            if (std::filesystem::exists(path))
                files.push_back(path);
        }
    }
    return files;
}

class ImmModel : public testing::Test {
protected:
    static void SetUpTestSuite()
    {
        if (!std::filesystem::exists(sharedData("imm_face_db/01-1m.asf")) ||
            !std::filesystem::exists(sharedData("candide3/candide3.wfm")))
            return;
        face_ = new vision::CandideMesh(
            vision::reduceCandideForTracking(aam::loadWfm(sharedData("candide3/candide3.wfm"))));
        std::vector<aam::FittedImage> training;
        for (const auto& path : immFiles(false, 1))
            training.push_back(aam::fitAnnotatedImage(*face_, aam::immScheme(), path));
        aam::ModelOptions options;
        options.resolution =
            48;  // the test's; the model's own resolution does not change the checks
        built_ = new aam::BuiltModel(aam::buildModel(*face_, training, options));
    }
    static void TearDownTestSuite()
    {
        delete built_;
        delete face_;
    }
    void SetUp() override
    {
        if (built_ == nullptr)
            GTEST_SKIP() << "IMM face database or CANDIDE-3 not in ../shared/data";
    }
    std::vector<aam::FittedImage> fitted(const std::vector<std::string>& files) const
    {
        std::vector<aam::FittedImage> out;
        for (const auto& path : files)
            out.push_back(aam::fitAnnotatedImage(*face_, aam::immScheme(), path));
        return out;
    }
    static inline vision::CandideMesh* face_ = nullptr;
    static inline aam::BuiltModel* built_ = nullptr;
};

TEST_F(ImmModel, IsBuiltFromThirtyPersons)
{
    EXPECT_EQ(built_->persons.size(), 30u);
    EXPECT_GE(built_->shape.modes.cols(), 5);
    EXPECT_GE(built_->appearance.modes.cols(), 5);
    EXPECT_LT(built_->appearance.modes.cols(),
              30);  // 95% of the variance, not every image its own mode
}

TEST_F(ImmModel, ReconstructsPersonsItNeverSaw)
{
    const auto results = aam::evaluateHeldOut(*built_, fitted(immFiles(true, 1)), false);
    ASSERT_EQ(results.size(), 10u);
    double shape = 0, shapeMean = 0, appearance = 0, appearanceMean = 0;
    for (const auto& r : results) {
        shape += r.shapeRmsPx, shapeMean += r.shapeMeanOnlyRmsPx;
        appearance += r.appearanceRms, appearanceMean += r.appearanceMeanOnlyRms;
    }
    // Measured at 48 px: shape 2.3 of 7.4 px, appearance 12 of 18 grey levels.
    EXPECT_LT(shape, 0.5 * shapeMean);
    EXPECT_LT(shape / 10, 4.0);
    EXPECT_LT(appearance, 0.8 * appearanceMean);
    EXPECT_LT(appearance / 10, 16.0);
}

TEST_F(ImmModel, RefusesToEvaluateAPersonItSawUnlessLabelled)
{
    const auto seen = fitted({immFiles(false, 2).front()});
    try {
        aam::evaluateHeldOut(*built_, seen, false);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()), "evaluation: " + seen.front().annotationPath +
                                             " is of person 01, whom the model was built from "
                                             "(--person-specific to allow it, labelled so)");
    }
    EXPECT_EQ(aam::evaluateHeldOut(*built_, seen, true).size(), 1u);
}

TEST_F(ImmModel, ItsFileReadsBackAsBuilt)
{
    const vision::AamModel written = aam::modelForFile(*built_);
    const std::string path = testing_support::freshOutputDir("aam_model_real") + "/imm48.aam";
    std::ofstream(path, std::ios::binary) << vision::encodeAamModel(written);
    const vision::AamModelFile back = vision::loadAamModel(path);
    ASSERT_TRUE(back.ok) << back.problem;
    EXPECT_EQ(back.model.mesh.vertices.size(), 84u);
    EXPECT_EQ(back.model.mesh.triangles.size(), 144u);
    EXPECT_EQ(back.model.mesh.animationUnits.size(), 6u);
    EXPECT_EQ(back.model.mesh.shapeUnits.size(), 10u);
    EXPECT_EQ(back.model.frameWidth, 48);
    EXPECT_EQ(back.model.pixels.size(), built_->frame.pixels.size());
    EXPECT_EQ(back.model.meanAppearance, written.meanAppearance);
    EXPECT_EQ(back.model.shapeModes, written.shapeModes);
}

TEST_F(ImmModel, TheMouthOpeningIsNotPartOfTheAppearance)
{
    // docs/aam-model-format.md: the mesh has no triangle over the opening, and the mean mouth is
    // half open, so the point between the lip corners (CANDIDE 31, 64) has no appearance pixel.
    const auto corner = [&](int number) {
        return built_->frame
            .meanShape[static_cast<std::size_t>(face_->indexOfCandideVertex(number))];
    };
    const Eigen::Vector2d centre = (corner(31) + corner(64)) / 2;
    const int x = static_cast<int>(std::lround(centre.x())),
              y = static_cast<int>(std::lround(centre.y()));
    for (const auto& p : built_->frame.pixels)
        EXPECT_FALSE(p.x == x && p.y == y) << "pixel " << x << "," << y;
}

}  // namespace
