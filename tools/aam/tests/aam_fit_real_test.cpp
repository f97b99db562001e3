// The runtime fit (vision::AamFitter, §5, 5.3.2) on real photographs of persons the model never
// saw: the model built from 30 IMM persons (every fourth held out, as `scripts/dev model`), each
// held-out person's frontal images fitted from the box of its annotation's CANDIDE fit (its
// centre, width and roll), the fitted vertices scored against that fit's projected vertices; and
// the turned heads (IMM types 3 and 4, ~30 degrees to the person's right and left), which must
// come out turned the right way. Skips when the IMM data is absent.
//
// The bounds are what the fit does now (docs/aam-fit.md), not what it must do: on these unseen
// persons it converges within 4 % of the face width on 6 of 20 frontal images (the aim: 17), and
// keeps 7 of 20 turned heads, every one turned the right way. They guard against going back.
#include "model_building.hpp"
#include "test_paths.hpp"
#include "vision/aam_fitter.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace {

using testing_support::sharedData;

std::vector<std::string> heldOutFiles(int kind)
{
    std::vector<std::string> files;
    for (int person = 4; person <= 40; person += 4) {
        for (const char sex : {'m', 'f'}) {
            char stem[32];
            std::snprintf(stem, sizeof stem, "imm_face_db/%02d-%d%c.asf", person, kind, sex);
            if (std::filesystem::exists(sharedData(stem)))
                files.push_back(sharedData(stem));
        }
    }
    return files;
}

class ImmFit : public testing::Test {
protected:
    static void SetUpTestSuite()
    {
        if (!std::filesystem::exists(sharedData("imm_face_db/01-1m.asf")) ||
            !std::filesystem::exists(sharedData("candide3/candide3.wfm")))
            return;
        face_ = new vision::CandideMesh(
            vision::reduceCandideForTracking(aam::loadWfm(sharedData("candide3/candide3.wfm"))));
        std::vector<aam::FittedImage> training;
        for (int person = 1; person <= 40; ++person) {
            if (person % 4 == 0)
                continue;
            for (const char sex : {'m', 'f'}) {
                char stem[32];
                std::snprintf(stem, sizeof stem, "imm_face_db/%02d-1%c.asf", person, sex);
                if (std::filesystem::exists(sharedData(stem)))
                    training.push_back(
                        aam::fitAnnotatedImage(*face_, aam::immScheme(), sharedData(stem)));
            }
        }
        model_ = new vision::AamModel(aam::modelForFile(aam::buildModel(*face_, training, {})));
    }
    static void TearDownTestSuite()
    {
        delete model_;
        delete face_;
    }
    void SetUp() override
    {
        if (model_ == nullptr)
            GTEST_SKIP() << "IMM face database or CANDIDE-3 not in ../shared/data";
    }

    struct Scored {
        vision::AamFitResult fit;
        double errorOverWidth = 0;  ///< rms vertex distance to the annotation's fit / face width
    };

    /// The held-out image fitted from its annotation's box.
    static Scored fitHeldOut(vision::AamFitter& fitter, const std::string& path)
    {
        const aam::FittedImage truth = aam::fitAnnotatedImage(*face_, aam::immScheme(), path);
        double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
        for (const Eigen::Vector2d& p : truth.shape) {
            x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
            y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
        }
        vision::AamStart start;
        start.centre = {static_cast<float>(0.5 * (x0 + x1)), static_cast<float>(0.5 * (y0 + y1))};
        start.width = static_cast<float>(x1 - x0);
        start.rollDegrees = static_cast<float>(truth.fit.rollRadians() * 180.0 / 3.14159265358979);
        vision::AamFaceState state;
        fitter.start(state, start);
        const cv::Mat& g = truth.grey;
        const vision::ConstImageView view{g.data, g.cols, g.rows, static_cast<int>(g.step[0]),
                                          vision::PixelFormat::Gray8};
        Scored s;
        s.fit = fitter.fit(view, state);
        double sum = 0;
        for (std::size_t v = 0; v < truth.shape.size(); ++v) {
            const double dx = s.fit.vertices[v].x - truth.shape[v].x();
            const double dy = s.fit.vertices[v].y - truth.shape[v].y();
            sum += dx * dx + dy * dy;
        }
        s.errorOverWidth = std::sqrt(sum / static_cast<double>(truth.shape.size())) / (x1 - x0);
        return s;
    }

    static inline vision::CandideMesh* face_ = nullptr;
    static inline vision::AamModel* model_ = nullptr;
};

TEST_F(ImmFit, HeldOutFrontalFacesConvergeFromTheirBoxes)
{
    vision::AamFitter fitter(*model_);
    int fits = 0, converged = 0;
    double error = 0, iterations = 0;
    for (int kind : {1, 2}) {
        for (const std::string& path : heldOutFiles(kind)) {
            const Scored s = fitHeldOut(fitter, path);
            ++fits;
            std::printf("%s: %s error/width=%.3f fit_error=%.2f iterations=%d yaw=%.1f\n",
                        std::filesystem::path(path).filename().c_str(),
                        vision::aamFitOutcomeName(s.fit.outcome), s.errorOverWidth, s.fit.fitError,
                        s.fit.iterations, s.fit.yawDegrees);
            if (s.fit.ok() && s.errorOverWidth < 0.04) {
                ++converged;
                error += s.errorOverWidth;
                iterations += s.fit.iterations;
            }
        }
    }
    std::printf("imm held-out frontal: fits=%d converged=%d error/width=%.3f iterations=%.1f\n",
                fits, converged, error / std::max(converged, 1),
                iterations / std::max(converged, 1));
    ASSERT_EQ(fits, 20);
    EXPECT_GE(converged, 5);
}

TEST_F(ImmFit, TurnedHeadsComeOutTurnedTheRightWay)
{
    vision::AamFitter fitter(*model_);
    int held = 0, rightSign = 0;
    double magnitude = 0;
    std::array<int, 2> side{};
    for (int kind : {3, 4}) {
        for (const std::string& path : heldOutFiles(kind)) {
            const Scored s = fitHeldOut(fitter, path);
            side[static_cast<std::size_t>(kind - 3)] +=
                s.fit.ok() && (kind == 3) == (s.fit.yawDegrees < 0.f) ? 1 : 0;
            std::printf("%s: %s error/width=%.3f yaw=%.1f\n",
                        std::filesystem::path(path).filename().c_str(),
                        vision::aamFitOutcomeName(s.fit.outcome), s.errorOverWidth,
                        s.fit.yawDegrees);
            if (!s.fit.ok())
                continue;
            ++held;
            // Type 3: turned to the person's right, the nose to the image's left: yaw < 0.
            rightSign += (kind == 3) == (s.fit.yawDegrees < 0.f) ? 1 : 0;
            magnitude += std::abs(s.fit.yawDegrees);
        }
    }
    std::printf("imm turned: held=%d right_sign=%d mean_abs_yaw=%.1f\n", held, rightSign,
                magnitude / std::max(held, 1));
    EXPECT_GE(held, 6);
    EXPECT_EQ(rightSign, held);
    EXPECT_GE(magnitude / std::max(held, 1), 15.0);  // turned, not left at the frontal start
    // Both sides: the heads turned to the person's left (their broad side in the photographs'
    // shadow) held 1 of 10 here from the frontal start alone (none from dlib's boxes in
    // mirror-eval), whose first steps lowered the gain instead of moving the mesh; they start
    // turned now (AamFitter::chooseStart): 3 of 10.
    vision::AamFitterOptions frontalOnly;
    frontalOnly.startYawDegrees = 0.f;
    vision::AamFitter frontalFitter(*model_, frontalOnly);
    std::array<int, 2> frontalSide{};
    for (int kind : {3, 4})
        for (const std::string& path : heldOutFiles(kind)) {
            const Scored s = fitHeldOut(frontalFitter, path);
            frontalSide[static_cast<std::size_t>(kind - 3)] +=
                s.fit.ok() && (kind == 3) == (s.fit.yawDegrees < 0.f) ? 1 : 0;
        }
    std::printf(
        "imm turned, held with the right sign, to the right / left: %d / %d (frontal start "
        "only: %d / %d)\n",
        side[0], side[1], frontalSide[0], frontalSide[1]);
    EXPECT_GE(side[0], 3);
    EXPECT_GE(side[1], 2);
    EXPECT_GT(side[1], frontalSide[1]);
}

}  // namespace
