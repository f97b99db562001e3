// Weighted Procrustes alignment (§5, 5.3.1, eqs. 45-53): the weights, the 4x4 solve, the iteration.
#include "shape_alignment.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aam {

namespace {

void checkShapes(const std::vector<Shape2d>& shapes)
{
    if (shapes.size() < 2)
        throw std::invalid_argument("shape alignment: " + std::to_string(shapes.size()) +
                                    " shapes, need 2");
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        if (shapes[i].size() != shapes[0].size() || shapes[i].size() < 2) {
            throw std::invalid_argument("shape alignment: shape " + std::to_string(i) + " has " +
                                        std::to_string(shapes[i].size()) + " vertices, shape 0 " +
                                        std::to_string(shapes[0].size()));
        }
    }
}

Shape2d meanOf(const std::vector<Shape2d>& shapes)
{
    Shape2d mean(shapes[0].size(), Eigen::Vector2d::Zero());
    for (const Shape2d& s : shapes) {
        for (std::size_t k = 0; k < s.size(); ++k)
            mean[k] += s[k];
    }
    for (auto& p : mean)
        p /= static_cast<double>(shapes.size());
    return mean;
}

/// The rms distance between corresponding vertices, over the rms distance of `b` from its centre.
double relativeMove(const Shape2d& a, const Shape2d& b)
{
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& p : b)
        centre += p;
    centre /= static_cast<double>(b.size());
    double moved = 0, size = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        moved += (a[k] - b[k]).squaredNorm();
        size += (b[k] - centre).squaredNorm();
    }
    return std::sqrt(moved / size);
}

}  // namespace

Eigen::Vector2d Similarity2d::operator()(const Eigen::Vector2d& p) const
{
    return {ax * p.x() - ay * p.y() + tx, ay * p.x() + ax * p.y() + ty};
}

Shape2d Similarity2d::operator()(const Shape2d& shape) const
{
    Shape2d out;
    out.reserve(shape.size());
    for (const auto& p : shape)
        out.push_back((*this)(p));
    return out;
}

Eigen::VectorXd vertexWeights(const std::vector<Shape2d>& shapes)
{
    checkShapes(shapes);
    const std::size_t n = shapes[0].size();
    Eigen::MatrixXd sum =
        Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    Eigen::MatrixXd sumSquares = sum;
    for (const Shape2d& s : shapes) {
        for (std::size_t k = 0; k < n; ++k) {
            for (std::size_t j = k + 1; j < n; ++j) {
                const double r = (s[k] - s[j]).norm();
                sum(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) += r;
                sumSquares(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) += r * r;
            }
        }
    }
    const double count = static_cast<double>(shapes.size());
    Eigen::MatrixXd variance =
        (sumSquares / count - (sum / count).cwiseProduct(sum / count)).cwiseMax(0.0);
    variance = variance + Eigen::MatrixXd(variance.transpose());
    // Shapes that are all alike (up to nothing) weigh every vertex alike; otherwise a vertex whose
    // distances never vary would weigh infinitely: floor its sum far below the rest.
    if (variance.sum() == 0)
        return Eigen::VectorXd::Ones(static_cast<Eigen::Index>(n));
    const Eigen::VectorXd summed = variance.rowwise().sum().cwiseMax(1e-12 * variance.sum());
    return summed.cwiseInverse();
}

Similarity2d alignSimilarity(const Shape2d& target, const Shape2d& moving, const Eigen::VectorXd& w)
{
    double X1 = 0, Y1 = 0, X2 = 0, Y2 = 0, Z = 0, W = 0, C1 = 0, C2 = 0;  // eqs. 48-53
    for (std::size_t k = 0; k < moving.size(); ++k) {
        const double wk = w(static_cast<Eigen::Index>(k));
        const Eigen::Vector2d& p1 = target[k];
        const Eigen::Vector2d& p2 = moving[k];
        X1 += wk * p1.x();
        Y1 += wk * p1.y();
        X2 += wk * p2.x();
        Y2 += wk * p2.y();
        Z += wk * p2.squaredNorm();
        W += wk;
        C1 += wk * (p1.x() * p2.x() + p1.y() * p2.y());
        C2 += wk * (p1.y() * p2.x() - p1.x() * p2.y());
    }
    Eigen::Matrix4d A;
    A << X2, -Y2, W, 0, Y2, X2, 0, W, Z, 0, X2, Y2, 0, Z, -Y2, X2;
    const Eigen::Vector4d s = A.fullPivLu().solve(Eigen::Vector4d(X1, Y1, C1, C2));
    return {s(0), s(1), s(2), s(3)};
}

AlignedShapes alignShapes(const std::vector<Shape2d>& shapes, const AlignmentOptions& options)
{
    checkShapes(shapes);
    AlignedShapes out;
    out.weights = vertexWeights(shapes);
    const Shape2d& first = options.reference != nullptr ? *options.reference : shapes[0];
    if (first.size() != shapes[0].size())
        throw std::invalid_argument("shape alignment: the reference's size is not the shapes'");
    for (const Shape2d& s : shapes)
        out.shapes.push_back(alignSimilarity(first, s, out.weights)(s));
    out.mean = meanOf(out.shapes);
    while (out.iterations < options.maxIterations) {
        ++out.iterations;
        const Shape2d mean = alignSimilarity(first, out.mean, out.weights)(out.mean);
        for (Shape2d& s : out.shapes)
            s = alignSimilarity(mean, s, out.weights)(s);
        const Shape2d next = meanOf(out.shapes);
        const double moved = relativeMove(next, out.mean);
        out.mean = next;
        if (moved < options.tolerance)
            break;
    }
    return out;
}

}  // namespace aam
