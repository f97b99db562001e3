// The per-image CANDIDE fit (§5, eq. 44): the eq. 44 start, then alternating linear solves of the
// similarity and of the units (see candide_fit.hpp for why).
#include "candide_fit.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aam {

namespace {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

/// Every unit of the mesh (shape first, then animation) as 2D displacements per marked point.
struct UnitColumns {
    Matrix dx, dy;  // rows: marked points; columns: units
};

UnitColumns unitColumns(const vision::CandideMesh& face, const std::vector<MarkedPoint>& marked)
{
    const auto units = face.shapeUnits.size() + face.animationUnits.size();
    UnitColumns c{
        Matrix::Zero(static_cast<Eigen::Index>(marked.size()), static_cast<Eigen::Index>(units)),
        Matrix::Zero(static_cast<Eigen::Index>(marked.size()), static_cast<Eigen::Index>(units))};
    std::size_t column = 0;
    for (const auto* list : {&face.shapeUnits, &face.animationUnits}) {
        for (const vision::CandideUnit& unit : *list) {
            for (std::size_t k = 0; k < unit.vertices.size(); ++k) {
                for (std::size_t i = 0; i < marked.size(); ++i) {
                    if (marked[i].vertex != unit.vertices[k])
                        continue;
                    c.dx(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(column)) +=
                        unit.displacements[k].x();
                    c.dy(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(column)) +=
                        unit.displacements[k].y();
                }
            }
            ++column;
        }
    }
    return c;
}

/// Least squares with a ridge on the columns from `firstRidged` on.
Vector ridgeSolve(const Matrix& A, const Vector& y, Eigen::Index firstRidged, double ridge)
{
    Matrix normal = A.transpose() * A;
    for (Eigen::Index j = firstRidged; j < normal.cols(); ++j)
        normal(j, j) += ridge;
    return normal.ldlt().solve(A.transpose() * y);
}

/// Eq. 44: t, a, b and the units' image displacements (k R sigma taken as sigma) in one solve.
Vector equation44(const vision::CandideMesh& face, const std::vector<MarkedPoint>& marked,
                  const UnitColumns& c, double priorWeight)
{
    const auto n = static_cast<Eigen::Index>(marked.size());
    const Eigen::Index units = c.dx.cols();
    Matrix A = Matrix::Zero(2 * n, 4 + units);
    Vector y(2 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector3f& v =
            face.vertices[static_cast<std::size_t>(marked[static_cast<std::size_t>(i)].vertex)];
        A.row(2 * i).head(4) << 1, 0, v.x(), v.y();
        A.row(2 * i + 1).head(4) << 0, 1, -v.y(), v.x();
        A.row(2 * i).tail(units) = c.dx.row(i);
        A.row(2 * i + 1).tail(units) = -c.dy.row(i);
        y.segment<2>(2 * i) = marked[static_cast<std::size_t>(i)].image;
    }
    return ridgeSolve(A, y, 4, priorWeight * priorWeight);
}

/// The marked vertices moved by the units, model frame (x, y).
Matrix deformedMarked(const vision::CandideMesh& face, const std::vector<MarkedPoint>& marked,
                      const UnitColumns& c, const Vector& units)
{
    Matrix g(static_cast<Eigen::Index>(marked.size()), 2);
    for (std::size_t i = 0; i < marked.size(); ++i) {
        const Eigen::Vector3f& v = face.vertices[static_cast<std::size_t>(marked[i].vertex)];
        const auto r = static_cast<Eigen::Index>(i);
        g(r, 0) = v.x() + c.dx.row(r).dot(units);
        g(r, 1) = v.y() + c.dy.row(r).dot(units);
    }
    return g;
}

/// The similarity with the units fixed: rows x: [1 0 gx gy], y: [0 1 -gy gx].
void solveSimilarity(const std::vector<MarkedPoint>& marked, const Matrix& g, CandideFit& fit)
{
    const auto n = static_cast<Eigen::Index>(marked.size());
    Matrix A(2 * n, 4);
    Vector y(2 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
        A.row(2 * i) << 1, 0, g(i, 0), g(i, 1);
        A.row(2 * i + 1) << 0, 1, -g(i, 1), g(i, 0);
        y.segment<2>(2 * i) = marked[static_cast<std::size_t>(i)].image;
    }
    const Vector s = A.colPivHouseholderQr().solve(y);
    fit.translation = s.head<2>();
    fit.a = s(2);
    fit.b = s(3);
}

/// The units with the similarity fixed: their displacements scaled and rotated by it.
Vector solveUnits(const vision::CandideMesh& face, const std::vector<MarkedPoint>& marked,
                  const UnitColumns& c, const CandideFit& fit, double priorWeight)
{
    const auto n = static_cast<Eigen::Index>(marked.size());
    Matrix A(2 * n, c.dx.cols());
    Vector y(2 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector3f& v =
            face.vertices[static_cast<std::size_t>(marked[static_cast<std::size_t>(i)].vertex)];
        A.row(2 * i) = fit.a * c.dx.row(i) + fit.b * c.dy.row(i);
        A.row(2 * i + 1) = fit.b * c.dx.row(i) - fit.a * c.dy.row(i);
        y.segment<2>(2 * i) = marked[static_cast<std::size_t>(i)].image -
                              imagePoint(fit.translation, fit.a, fit.b, v.x(), v.y());
    }
    const double k = fit.scale();
    return ridgeSolve(A, y, 0, (priorWeight * k) * (priorWeight * k));
}

void storeUnits(const vision::CandideMesh& face, const Vector& units, CandideFit& fit)
{
    fit.sigma.assign(face.shapeUnits.size(), 0.f);
    fit.tau.assign(face.animationUnits.size(), 0.f);
    for (std::size_t j = 0; j < fit.sigma.size(); ++j)
        fit.sigma[j] = static_cast<float>(units(static_cast<Eigen::Index>(j)));
    for (std::size_t j = 0; j < fit.tau.size(); ++j) {
        fit.tau[j] = static_cast<float>(units(static_cast<Eigen::Index>(fit.sigma.size() + j)));
    }
}

void measureResiduals(const vision::CandideMesh& face, const std::vector<MarkedPoint>& marked,
                      CandideFit& fit)
{
    const std::vector<Eigen::Vector2d> projected = projectedVertices(face, fit);
    double sum = 0;
    fit.maxResidualPx = 0;
    for (const MarkedPoint& m : marked) {
        const double r = (projected[static_cast<std::size_t>(m.vertex)] - m.image).norm();
        sum += r * r;
        fit.maxResidualPx = std::max(fit.maxResidualPx, r);
    }
    fit.rmsResidualPx = std::sqrt(sum / static_cast<double>(marked.size()));
}

}  // namespace

double CandideFit::scale() const
{
    return std::hypot(a, b);
}
double CandideFit::rollRadians() const
{
    return std::atan2(b, a);
}

Eigen::Vector2d imagePoint(const Eigen::Vector2d& t, double a, double b, double x, double y)
{
    return t + Eigen::Vector2d(a * x + b * y, b * x - a * y);
}

CandideFit fitCandide(const vision::CandideMesh& face, const std::vector<MarkedPoint>& marked,
                      const CandideFitOptions& options)
{
    const std::size_t unknowns = 4 + face.shapeUnits.size() + face.animationUnits.size();
    if (2 * marked.size() < unknowns) {
        throw std::invalid_argument("CANDIDE fit: " + std::to_string(marked.size()) +
                                    " marked points for " + std::to_string(unknowns) +
                                    " unknowns (need at least " +
                                    std::to_string((unknowns + 1) / 2) + ")");
    }
    const UnitColumns c = unitColumns(face, marked);
    const Vector start = equation44(face, marked, c, options.priorWeight);
    CandideFit fit;
    fit.translation = start.head<2>();
    fit.a = start(2);
    fit.b = start(3);
    Vector units = start.tail(c.dx.cols()) / fit.scale();
    for (int round = 0; round < options.rounds; ++round) {
        solveSimilarity(marked, deformedMarked(face, marked, c, units), fit);
        units = solveUnits(face, marked, c, fit, options.priorWeight);
    }
    storeUnits(face, units, fit);
    measureResiduals(face, marked, fit);
    return fit;
}

std::vector<Eigen::Vector2d> projectedVertices(const vision::CandideMesh& face,
                                               const CandideFit& fit)
{
    const std::vector<Eigen::Vector3f> g = vision::deformedVertices(face, fit.sigma, fit.tau);
    std::vector<Eigen::Vector2d> out;
    out.reserve(g.size());
    for (const Eigen::Vector3f& v : g)
        out.push_back(imagePoint(fit.translation, fit.a, fit.b, v.x(), v.y()));
    return out;
}

}  // namespace aam
