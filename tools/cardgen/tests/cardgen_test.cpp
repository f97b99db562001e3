// cardgen: every scenario renders, writes its files, and its truth matches the drawn card.

#include "scenarios.hpp"
#include "sequence_writer.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using cardgen::FrameSpec;
using cardgen::Scenario;
using testing_support::freshOutputDir;
using testing_support::sharedData;

/// Signed distance of (x, y) to the quad's outline, positive inside.
double insideDistance(const vision::Quad& q, double x, double y)
{
    double d = 1e9;
    for (int i = 0; i < 4; ++i) {
        const vision::Point2f a = q[i], b = q[(i + 1) % 4];
        const double ex = b.x - a.x, ey = b.y - a.y;
        d = std::min(d, (ex * (y - a.y) - ey * (x - a.x)) / std::hypot(ex, ey));
    }
    return d;
}

bool clockwiseConvex(const vision::Quad& q)
{
    for (int i = 0; i < 4; ++i) {
        const vision::Point2f a = q[i], b = q[(i + 1) % 4], c = q[(i + 2) % 4];
        // y down: clockwise on screen is a positive cross product.
        if ((b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x) <= 0.0)
            return false;
    }
    return true;
}

/// Corner 0 is the top-left one: the corner nearest to the top-left of the quad's bounding box.
bool startsTopLeft(const vision::Quad& q)
{
    int best = 0;
    double bestScore = 1e18;
    for (int i = 0; i < 4; ++i) {
        const double score = q[i].x + q[i].y;
        if (score < bestScore) {
            bestScore = score;
            best = i;
        }
    }
    return best == 0;
}

cv::Size kSize(720, 480);

TEST(Cardgen, EveryScenarioIsKnownAndRejectsBadArguments)
{
    EXPECT_EQ(cardgen::scenarios().size(), 17u);
    EXPECT_EQ(cardgen::findScenario("nope"), nullptr);
    EXPECT_THROW(Scenario("nope", kSize, 10, 1), std::runtime_error);
    EXPECT_THROW(Scenario("perspective", kSize, 1, 1), std::runtime_error);
    EXPECT_THROW(Scenario("perspective", cv::Size(32, 32), 10, 1), std::runtime_error);
}

TEST(Cardgen, TruthIsClockwiseFromTopLeftForEveryFrameOfEveryScenarioAndSeed)
{
    for (std::uint32_t seed = 1; seed <= 3; ++seed)
        for (const auto& info : cardgen::scenarios()) {
            const Scenario s(info.name, kSize, cardgen::kDefaultFrames, seed);
            const FrameSpec first = s.frame(0);
            // Frame 0: the card covers the whole view.
            EXPECT_TRUE(first.card);
            EXPECT_LT(first.quad[0].x, -0.5f);
            EXPECT_GT(first.quad[2].y, kSize.height - 0.5f);
            int withoutCard = 0;
            int outsideCorners = 0;
            for (int i = 0; i < s.frames(); ++i) {
                const FrameSpec f = s.frame(i);
                if (!f.card) {
                    ++withoutCard;
                    continue;
                }
                ASSERT_TRUE(clockwiseConvex(f.quad)) << info.name << " frame " << i;
                ASSERT_TRUE(startsTopLeft(cardgen::truthCorners(f.quad)))
                    << info.name << " frame " << i;
                // The first scenarios never turn the card that far: their truth is the drawn quad.
                if (!cardgen::isHardScenario(info.name)) {
                    ASSERT_TRUE(startsTopLeft(f.quad)) << info.name << " frame " << i;
                }
                for (const auto& p : f.quad)
                    outsideCorners += i > 0 && (p.x < 0 || p.y < 0 || p.x > kSize.width - 1 ||
                                                p.y > kSize.height - 1);
                if (f.distractor && i > 0) {
                    // Never touching the card: 10 px between them at least.
                    for (const auto& p : f.distractorQuad)
                        EXPECT_LT(insideDistance(f.quad, p.x, p.y), -10.0) << info.name << " " << i;
                    for (const auto& p : f.quad)
                        EXPECT_LT(insideDistance(f.distractorQuad, p.x, p.y), -10.0);
                }
            }
            const std::string name = info.name;
            if (cardgen::isHardScenario(name)) {
                // The hard family's own checks are below; its cards may touch a border.
                if (name == "hard_corner" || name == "hard") {
                    EXPECT_GT(outsideCorners, 10) << name << " seed " << seed;
                }
                EXPECT_EQ(withoutCard, 0) << name;
            } else if (name == "lost_and_back") {
                EXPECT_GE(withoutCard, 30) << name;
            } else {
                EXPECT_EQ(withoutCard, 0) << name;
            }
            if (name == "corner_out") {
                EXPECT_GT(outsideCorners, 30) << name;
            } else if (name != "lost_and_back" && !cardgen::isHardScenario(name)) {
                EXPECT_EQ(outsideCorners, 0) << name << ": the card should stay in view";
            }
        }
}

TEST(Cardgen, TruthRowsHaveEmptyCornerFieldsWithoutCard)
{
    FrameSpec spec;
    spec.card = false;
    EXPECT_EQ(cardgen::truthRow(17, spec), "17,,,,,,,,");
    spec.card = true;
    spec.quad = {vision::Point2f{-3.5f, 2.f}, vision::Point2f{100.25f, 2.f},
                 vision::Point2f{100.25f, 50.125f}, vision::Point2f{-3.5f, 50.125f}};
    EXPECT_EQ(cardgen::truthRow(3, spec),
              "3,-3.500,2.000,100.250,2.000,100.250,50.125,-3.500,50.125");
    // lost_and_back has such frames, and only those have no card.
    const Scenario s("lost_and_back", kSize, cardgen::kDefaultFrames, 1);
    EXPECT_FALSE(s.frame(60).card);
    EXPECT_TRUE(s.frame(10).card);
}

TEST(Cardgen, TruthStartsAtTheTopLeftCornerOfATurnedCard)
{
    // Turned by 60 degrees: the card's own top-left corner is now its top-right one on screen.
    FrameSpec spec;
    spec.quad = cardgen::projectCard({300.0, 200.0, 60.0, 0.0, 0.0, 1.05}, 648.0);
    ASSERT_FALSE(startsTopLeft(spec.quad));
    const vision::Quad t = cardgen::truthCorners(spec.quad);
    EXPECT_TRUE(startsTopLeft(t));
    EXPECT_TRUE(clockwiseConvex(t));
    char row[200];
    std::snprintf(row, sizeof row, "4,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f", t[0].x, t[0].y,
                  t[1].x, t[1].y, t[2].x, t[2].y, t[3].x, t[3].y);
    EXPECT_EQ(cardgen::truthRow(4, spec), row);
}

TEST(Cardgen, CornerOutMovesOnlyTheTopLeftCornerOut)
{
    const Scenario s("corner_out", kSize, cardgen::kDefaultFrames, 1);
    float lowest = 0.0f;
    for (int i = 1; i < s.frames(); ++i) {
        const vision::Quad q = s.frame(i).quad;
        lowest = std::min(lowest, q[0].y);
        for (int k = 1; k < 4; ++k) {
            EXPECT_GE(q[k].x, 0.0f);
            EXPECT_GE(q[k].y, 0.0f);
        }
    }
    EXPECT_NEAR(lowest, -35.0f, 0.5f);
}

TEST(Cardgen, OccluderCoversTheRightEdgeAndThenTheBottomRightCorner)
{
    const Scenario s("occluder", kSize, cardgen::kDefaultFrames, 1);
    const cv::Mat bg(kSize, CV_8UC3, cv::Scalar(0, 0, 0));
    auto covered = [&](int i, vision::Point2f p) {
        FrameSpec f = s.frame(i);
        f.noiseSigma = 0;
        const cv::Mat img = cardgen::renderFrame(bg, f, 1);
        const cv::Vec3b px = img.at<cv::Vec3b>(static_cast<int>(std::lround(p.y)),
                                               static_cast<int>(std::lround(p.x)));
        return px[2] > 150 && px[1] > 110;  // skin (BGR): red and fairly green, not card green
    };
    const vision::Quad q50 = s.frame(50).quad;
    const vision::Point2f rightMid{0.5f * (q50[1].x + q50[2].x) - 3, 0.5f * (q50[1].y + q50[2].y)};
    EXPECT_TRUE(covered(50, rightMid));
    EXPECT_FALSE(covered(50, {q50[0].x + 5, q50[0].y + 5}));
    const vision::Quad q100 = s.frame(100).quad;
    EXPECT_TRUE(covered(100, {q100[2].x - 2, q100[2].y - 2}));
    EXPECT_FALSE(covered(5, rightMid));
}

class CardgenFiles : public ::testing::TestWithParam<std::string> {};

TEST_P(CardgenFiles, WritesFramesTruthAndDescriptionMatchingTheDrawnCard)
{
    const std::string name = GetParam();
    cardgen::GenerateOptions o;
    o.scenario = name;
    o.outDir = freshOutputDir("cardgen_" + name);
    o.frames = 6;
    o.size = cv::Size(360, 240);  // small: fast
    o.dataDir = sharedData("");
    const cardgen::GeneratedSequence seq = cardgen::generateSequence(o);
    EXPECT_EQ(seq.frames, 6);
    ASSERT_TRUE(fs::exists(fs::path(o.outDir) / "scenario.txt"));

    std::ifstream truth(fs::path(o.outDir) / "truth.csv");
    std::string line;
    ASSERT_TRUE(std::getline(truth, line));
    EXPECT_EQ(line, "frame,x0,y0,x1,y1,x2,y2,x3,y3");
    const Scenario scenario(name, o.size, o.frames, o.seed);
    for (int i = 0; i < 6; ++i) {
        ASSERT_TRUE(std::getline(truth, line)) << "row " << i;
        const FrameSpec spec = scenario.frame(i);
        EXPECT_EQ(line, cardgen::truthRow(i, spec));
        char file[32];
        std::snprintf(file, sizeof file, "frame_%05d.png", i);
        const cv::Mat img = cv::imread((fs::path(o.outDir) / file).string(), cv::IMREAD_COLOR);
        ASSERT_EQ(img.size(), o.size) << file;
        if (!spec.card)
            continue;
        // Parse the row back and check the pixels: well inside the card = the card's colour
        // (chromaticity near the paint's), well outside = not changed by the card.
        float v[8];
        int frame = -1;
        ASSERT_EQ(std::sscanf(line.c_str(), "%d,%f,%f,%f,%f,%f,%f,%f,%f", &frame, &v[0], &v[1],
                              &v[2], &v[3], &v[4], &v[5], &v[6], &v[7]),
                  9);
        vision::Quad q;
        for (int k = 0; k < 4; ++k)
            q[k] = {v[2 * k], v[2 * k + 1]};
        const cv::Mat bg = cardgen::loadBackground(seq.background, o.size);
        const double paint[3] = {static_cast<double>(spec.paint.blue),
                                 static_cast<double>(spec.paint.green),
                                 static_cast<double>(spec.paint.red)};
        const double paintSum = paint[0] + paint[1] + paint[2];
        int inside = 0, insideOk = 0, outside = 0, outsideOk = 0;
        for (int y = 2; y < img.rows; y += 7)
            for (int x = 3; x < img.cols; x += 7) {
                const double d = insideDistance(q, x, y);
                const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
                const cv::Vec3b b = bg.at<cv::Vec3b>(y, x);
                if (d > 2.0 && !spec.hand) {
                    ++inside;
                    const double sum = p[0] + p[1] + p[2] + 1e-9;
                    bool ok = true;
                    for (int c = 0; c < 3; ++c)
                        ok = ok && std::abs(p[c] / sum - paint[c] / paintSum) <
                                       0.06 + 0.01 * spec.noiseSigma;
                    insideOk += ok;
                } else if (d < -2.0 && !spec.distractor && !spec.interlace && !spec.hand &&
                           !spec.backHand && spec.blurSigma == 0.0) {
                    ++outside;
                    bool ok = true;
                    const double tol =
                        4.0 * spec.noiseSigma + 3.0 + 255.0 * std::abs(spec.gain - 1);
                    for (int c = 0; c < 3; ++c)
                        ok = ok && std::abs(p[c] - std::min(255.0, b[c] * spec.gain)) <= tol;
                    outsideOk += ok;
                }
            }
        if (!spec.hand && spec.gain < 1.2) {  // clipping changes the chromaticity
            ASSERT_GT(inside, 20) << name << " frame " << i;
            EXPECT_GE(insideOk, inside * 97 / 100) << name << " frame " << i;
        }
        if (outside > 0) {
            EXPECT_GE(outsideOk, outside * 99 / 100) << name << " frame " << i;
        }
    }
    EXPECT_FALSE(std::getline(truth, line)) << "extra rows";
}

INSTANTIATE_TEST_SUITE_P(AllScenarios, CardgenFiles,
                         ::testing::Values("perspective", "light_ramp", "noise", "gain_steps",
                                           "occluder", "corner_out", "fast_interlace", "distractor",
                                           "lost_and_back", "hard_motion", "hard_light",
                                           "hard_shading", "hard_noise", "hard_occluder",
                                           "hard_corner", "hard_distractors", "hard"));

}  // namespace
