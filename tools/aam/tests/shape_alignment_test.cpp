// Weighted Procrustes (§5, 5.3.1, eqs. 45-53): a known similarity recovered, copies of one shape
// aligned onto it, an unsteady vertex weighted least, real synthesized shapes converging.
#include "shape_alignment.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

aam::Shape2d square()
{
    return {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {5, 3}};
}

TEST(ShapeAlignment, RecoversAKnownSimilarity)
{
    const aam::Similarity2d truth{1.5 * std::cos(0.4), 1.5 * std::sin(0.4), 7, -3};
    const aam::Shape2d moving = square();
    const aam::Similarity2d s =
        aam::alignSimilarity(truth(moving), moving, Eigen::VectorXd::Ones(5));
    EXPECT_NEAR(s.ax, truth.ax, 1e-12);
    EXPECT_NEAR(s.ay, truth.ay, 1e-12);
    EXPECT_NEAR(s.tx, truth.tx, 1e-12);
    EXPECT_NEAR(s.ty, truth.ty, 1e-12);
}

TEST(ShapeAlignment, CopiesOfOneShapeAlignOntoTheFirst)
{
    std::vector<aam::Shape2d> shapes{square()};
    for (int i = 1; i < 6; ++i) {
        const double phi = 0.2 * i, k = 0.5 + 0.3 * i;
        shapes.push_back(
            aam::Similarity2d{k * std::cos(phi), k * std::sin(phi), 3.0 * i, -2.0 * i}(square()));
    }
    const aam::AlignedShapes aligned = aam::alignShapes(shapes);
    for (const auto& s : aligned.shapes) {
        for (std::size_t v = 0; v < s.size(); ++v)
            EXPECT_LT((s[v] - square()[v]).norm(), 1e-9);
    }
    for (std::size_t v = 0; v < 5; ++v)
        EXPECT_LT((aligned.mean[v] - square()[v]).norm(), 1e-9);
}

TEST(ShapeAlignment, AReferenceGivesTheFrame)
{
    const aam::Similarity2d turn{2 * std::cos(0.5), 2 * std::sin(0.5), 4, 1};
    const aam::Shape2d reference = turn(square());
    aam::AlignmentOptions options;
    options.reference = &reference;
    const aam::AlignedShapes aligned = aam::alignShapes({square(), square()}, options);
    for (std::size_t v = 0; v < 5; ++v)
        EXPECT_LT((aligned.mean[v] - reference[v]).norm(), 1e-9);
    EXPECT_EQ(aligned.weights, Eigen::VectorXd::Ones(5));  // identical shapes: all alike
}

TEST(ShapeAlignment, TheUnsteadyVertexWeighsLeast)
{
    std::mt19937 random(3);
    std::normal_distribution<double> jitter(0, 1);
    std::vector<aam::Shape2d> shapes;
    for (int i = 0; i < 50; ++i) {
        aam::Shape2d s = square();
        for (auto& p : s)
            p += 0.05 * Eigen::Vector2d(jitter(random), jitter(random));
        s[4] += 2.0 * Eigen::Vector2d(jitter(random), jitter(random));  // the centre point wanders
        shapes.push_back(s);
    }
    const Eigen::VectorXd w = aam::vertexWeights(shapes);
    Eigen::Index least = 0;
    w.minCoeff(&least);
    EXPECT_EQ(least, 4);
    EXPECT_LT(w(4),
              0.4 * w.head(4).minCoeff());  // its variance is in every sum, four times in its own
    // Aligned, the steady corners agree far better than the wandering point.
    const aam::AlignedShapes aligned = aam::alignShapes(shapes);
    EXPECT_LT(aligned.iterations, 100);
    double corner = 0, centre = 0;
    for (const auto& s : aligned.shapes) {
        corner += (s[0] - aligned.mean[0]).norm();
        centre += (s[4] - aligned.mean[4]).norm();
    }
    EXPECT_LT(corner * 5, centre);
}

TEST(ShapeAlignment, BadSetsAreOneLine)
{
    try {
        aam::alignShapes({square()});
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "shape alignment: 1 shapes, need 2");
    }
    aam::Shape2d short_ = square();
    short_.pop_back();
    try {
        aam::alignShapes({square(), short_});
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "shape alignment: shape 1 has 4 vertices, shape 0 5");
    }
}

}  // namespace
