// mirror-eval aam's scoring: NME on known point sets (normalised by the outer eye corners, inner
// points apart from the jaw and brows), the scheme tables bringing truth and estimates to the
// same CANDIDE vertices, Pearson's correlation, the FGNet-iBUG pairs.
#include "aam_scoring.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

namespace {

using mirror_eval::CandidePoints;

/// A truth with the eye corners 100 px apart and a few inner, brow and jaw points.
CandidePoints knownTruth()
{
    return {{20, {300, 200}}, {53, {200, 200}}, {5, {250, 250}}, {16, {300, 170}},
            {10, {250, 350}}, {87, {250, 290}}, {40, {250, 300}}};
}

TEST(AamScoring, NmeIsTheMeanDistanceOverTheEyeCornerDistance)
{
    const CandidePoints truth = knownTruth();
    CandidePoints estimate = truth;
    estimate[5] += Eigen::Vector2d(3, 4);    // 5 px off: an inner point
    estimate[10] += Eigen::Vector2d(0, 10);  // 10 px off: the jaw
    estimate[99] = {0, 0};                   // a vertex the truth lacks: not compared
    const double eyes = *mirror_eval::eyeCornerDistance(truth);
    EXPECT_DOUBLE_EQ(eyes, 100.0);
    const auto nme = mirror_eval::frameNme(truth, estimate, eyes);
    ASSERT_TRUE(nme);
    // Inner: 20, 53, 5, 87, 40 (5 points), one 5 px off.
    EXPECT_EQ(nme->innerPoints, 5);
    EXPECT_NEAR(nme->inner, 0.05 / 5, 1e-12);
    // All: the 7 truth points, 5 + 10 px off.
    EXPECT_EQ(nme->allPoints, 7);
    EXPECT_NEAR(nme->all, 0.15 / 7, 1e-12);
}

TEST(AamScoring, OnlyTheGivenVerticesAreComparedAndNoneIsNoScore)
{
    const CandidePoints truth = knownTruth();
    CandidePoints estimate = truth;
    estimate[5] += Eigen::Vector2d(10, 0);
    const CandidePoints only{{5, {0, 0}}, {20, {0, 0}}};
    const auto nme = mirror_eval::frameNme(truth, estimate, 100.0, &only);
    ASSERT_TRUE(nme);
    EXPECT_EQ(nme->allPoints, 2);
    EXPECT_NEAR(nme->inner, 0.05, 1e-12);
    EXPECT_FALSE(mirror_eval::frameNme(truth, CandidePoints{{10, {0, 0}}}, 100.0));
    EXPECT_FALSE(mirror_eval::frameNme(truth, estimate, 0.0));
    EXPECT_FALSE(mirror_eval::eyeCornerDistance(CandidePoints{{20, {1, 1}}}));
}

TEST(AamScoring, GroupsAreJawBrowsAndTheInnerRest)
{
    using mirror_eval::PointGroup;
    for (int jaw : {10, 30, 32, 63, 65})
        EXPECT_EQ(mirror_eval::pointGroupOf(jaw), PointGroup::Jaw) << jaw;
    for (int brow : {15, 16, 17, 18, 48, 49, 50, 51})
        EXPECT_EQ(mirror_eval::pointGroupOf(brow), PointGroup::Brow) << brow;
    for (int inner : {5, 6, 7, 8, 20, 23, 31, 53, 56, 64, 87, 88, 111})
        EXPECT_EQ(mirror_eval::pointGroupOf(inner), PointGroup::Inner) << inner;
}

TEST(AamScoring, MouthOpeningIsTheInnerLipsApartOverTheEyes)
{
    EXPECT_NEAR(*mirror_eval::mouthOpening(knownTruth(), 100.0), 0.1, 1e-12);
    EXPECT_FALSE(mirror_eval::mouthOpening(CandidePoints{{87, {0, 0}}}, 100.0));
}

/// An FGNet (Cootes 68) annotation and the iBUG one that marks the same places, built from the
/// FGNet-iBUG table itself: each iBUG point at the FGNet place it pairs with.
struct PairedMarkups {
    std::vector<Eigen::Vector2d> fgnet, ibug;
};
PairedMarkups pairedMarkups()
{
    PairedMarkups m;
    for (int i = 0; i < 68; ++i)
        m.fgnet.emplace_back(100 + 7 * (i % 10), 100 + 11 * (i / 10));
    m.ibug.assign(68, Eigen::Vector2d(0, 0));
    for (const aam::FgnetIbugPair& pair : aam::fgnetIbugPairs()) {
        const Eigen::Vector2d at = pair.fgnet.of(m.fgnet);
        for (int k = 0; k < pair.ibug.count(); ++k)
            m.ibug[static_cast<std::size_t>(pair.ibug.points[static_cast<std::size_t>(k)])] = at;
    }
    return m;
}

TEST(AamScoring, TheTablesBringFgnetAndIbugToTheSameCandideVertices)
{
    const PairedMarkups m = pairedMarkups();
    const CandidePoints truth = mirror_eval::candidePointsOf(aam::fgnetScheme(), m.fgnet);
    const CandidePoints dlib = mirror_eval::candidePointsOf(aam::ibugScheme(), m.ibug);
    EXPECT_EQ(truth.size(), aam::fgnetScheme().rows.size());
    EXPECT_EQ(dlib.size(), aam::ibugScheme().rows.size());
    // Where both tables have a vertex, the paired markups put it at the same place.
    const double eyes = *mirror_eval::eyeCornerDistance(truth);
    const auto nme = mirror_eval::frameNme(truth, dlib, eyes);
    ASSERT_TRUE(nme);
    EXPECT_EQ(nme->allPoints, static_cast<int>(aam::ibugScheme().rows.size()));
    EXPECT_NEAR(nme->all, 0.0, 1e-12);
    // The outer eye corners: FGNet 32 (left) and 27 (right) are CANDIDE 20 and 53.
    EXPECT_EQ(truth.at(20), m.fgnet[32]);
    EXPECT_EQ(truth.at(53), m.fgnet[27]);
}

TEST(AamScoring, FgnetIbugPairsScoreZeroOnTheSamePlacesAndCountTheGroups)
{
    PairedMarkups m = pairedMarkups();
    const mirror_eval::PairNme same = mirror_eval::fgnetIbugNme(m.fgnet, m.ibug);
    EXPECT_NEAR(same.all, 0.0, 1e-12);
    EXPECT_EQ(same.allPoints, static_cast<int>(aam::fgnetIbugPairs().size()));
    EXPECT_EQ(same.innerPoints, 30);  // eyes 8, nose 6, lips 16
    EXPECT_EQ(same.innerAndChinPoints, 31);
    EXPECT_EQ(same.withCentresPoints, 33);  // and the pupils and the mouth centre
    EXPECT_EQ(same.withCentresAndChinPoints, 34);
    // The centres: each iBUG contour's mean against FGNet's own centre point.
    PairedMarkups centred = m;
    for (const auto& [fgnet, first, last] : {std::tuple{31, 36, 41}, {36, 42, 47}, {66, 60, 67}})
        for (int i = first; i <= last; ++i)
            centred.ibug[static_cast<std::size_t>(i)] = m.fgnet[static_cast<std::size_t>(fgnet)];
    const mirror_eval::PairNme centres = mirror_eval::fgnetIbugNme(m.fgnet, centred.ibug);
    const mirror_eval::PairNme shifted = [&] {
        PairedMarkups moved = centred;
        for (int i = 60; i <= 67; ++i)  // the mouth centre off by a tenth of the eye distance
            moved.ibug[static_cast<std::size_t>(i)] +=
                Eigen::Vector2d(0.1 * (m.fgnet[27] - m.fgnet[32]).norm(), 0);
        return mirror_eval::fgnetIbugNme(m.fgnet, moved.ibug);
    }();
    EXPECT_NEAR(shifted.withCentres * 33 - centres.withCentres * 33,
                0.1 + (shifted.inner - centres.inner) * 30, 1e-9);
    m.ibug[8] += Eigen::Vector2d(0, 0.5 * (m.fgnet[27] - m.fgnet[32]).norm());  // the chin off
    const mirror_eval::PairNme chin = mirror_eval::fgnetIbugNme(m.fgnet, m.ibug);
    EXPECT_NEAR(chin.inner, 0.0, 1e-12);
    EXPECT_NEAR(chin.innerAndChin, 0.5 / 31, 1e-12);
    EXPECT_THROW(mirror_eval::fgnetIbugNme(m.fgnet, {}), std::invalid_argument);
}

TEST(AamScoring, AWrongPointCountIsRefused)
{
    EXPECT_THROW(mirror_eval::candidePointsOf(aam::fgnetScheme(), std::vector<Eigen::Vector2d>(58)),
                 std::invalid_argument);
}

TEST(AamScoring, PearsonOfKnownSeries)
{
    const std::vector<double> x{1, 2, 3, 4, 5};
    EXPECT_NEAR(mirror_eval::pearson(x, {2, 4, 6, 8, 10}), 1.0, 1e-12);
    EXPECT_NEAR(mirror_eval::pearson(x, {5, 4, 3, 2, 1}), -1.0, 1e-12);
    // Hand-computed: x against {1, 3, 2, 5, 4}: cov 2.0, var 2.0 and 2.0 (population): 0.8.
    EXPECT_NEAR(mirror_eval::pearson(x, {1, 3, 2, 5, 4}), 0.8, 1e-12);
    EXPECT_TRUE(std::isnan(mirror_eval::pearson(x, {1, 1, 1, 1, 1})));
    EXPECT_TRUE(std::isnan(mirror_eval::pearson({1}, {1})));
    EXPECT_TRUE(std::isnan(mirror_eval::pearson(x, {1, 2})));
}

}  // namespace
