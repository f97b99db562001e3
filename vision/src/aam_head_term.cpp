// The 3D term of the AAM fit (§5, eqs. 83 and 86), assembled vertex by vertex. The 2D shape's
// derivative in the increment (dq, dp) is that of the inverse composition: vertex v moves by
// -L_v (S*_v dq + S_v dp), L_v its vertex map's linear part; the head's derivative is the
// projection's (aam_head_projection). K multiplies the sums once, not every Jacobian entry
// (5.3.4: factor K out).
#include "aam_head_term.hpp"

namespace vision::aam {

namespace {

/// Units kept from drifting where the 2D shape cannot tell them apart, in the 3D term's units.
constexpr double kUnitRidge = 5.0;

}  // namespace

double headTermEnergy(const Tables& t, const AamHead& head, const HeadTermInput& in,
                      float* points) noexcept
{
    projectHead(t, head, points, nullptr);
    const double toFrame = 1.0 / in.frameScale;
    double sum = 0.0;
    for (int k = 0; k < 2 * t.vertices; ++k) {
        const double e = (in.shape[k] - points[k]) * toFrame;
        sum += e * e;
    }
    for (float u : head.sigma)
        sum += kUnitRidge * u * u;
    for (float u : head.tau)
        sum += kUnitRidge * u * u;
    return in.weight * sum;
}

void addHeadTerm(const Tables& t, const AamHead& head, const HeadTermInput& in, float* points,
                 HeadJacobian* jacobian, ParameterMatrix& hessian, ParameterVector& rhs) noexcept
{
    const int m = t.shapeModeCount;
    const int headFirst = 6 + m;
    const int n = headFirst + kHeadParameters;
    projectHead(t, head, points, jacobian);
    const double toFrame = 1.0 / in.frameScale;
    Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, kMaxParameters> j(2, n);
    ParameterMatrix sum = ParameterMatrix::Zero(n, n);
    ParameterVector gradient = ParameterVector::Zero(n);
    j.leftCols<2>().setZero();
    for (int v = 0; v < t.vertices; ++v) {
        const Eigen::Matrix2f& l = in.vertexMaps[v].linear;
        const Eigen::Matrix<float, 2, 4> dq = -l * t.similarity.block<2, 4>(2 * v, 0);
        j.middleCols<4>(2) = dq.cast<double>() * toFrame;
        for (int k = 0; k < m; ++k)
            j.col(6 + k) = (-l * t.shapeModes.col(k).segment<2>(2 * v)).cast<double>() * toFrame;
        j.rightCols<kHeadParameters>() = -jacobian[v].cast<double>() * toFrame;
        const Eigen::Vector2d e((in.shape[2 * v] - points[2 * v]) * toFrame,
                                (in.shape[2 * v + 1] - points[2 * v + 1]) * toFrame);
        for (int a = 2; a < n; ++a) {
            for (int b = 2; b <= a; ++b)
                sum(a, b) += j(0, a) * j(0, b) + j(1, a) * j(1, b);
            gradient(a) += j(0, a) * e.x() + j(1, a) * e.y();
        }
    }
    const double k = in.weight;
    const int firstUnit = headFirst + 6;
    for (int u = 0; u < kAamShapeUnits + kAamAnimationUnits; ++u) {
        const double value = u < kAamShapeUnits
                                 ? head.sigma[static_cast<std::size_t>(u)]
                                 : head.tau[static_cast<std::size_t>(u - kAamShapeUnits)];
        sum(firstUnit + u, firstUnit + u) += kUnitRidge;
        gradient(firstUnit + u) += kUnitRidge * value;
    }
    hessian.triangularView<Eigen::Lower>() += k * sum;
    rhs -= k * gradient;
    if (in.shapeUnitsFrozen) {
        for (int u = 0; u < kAamShapeUnits; ++u) {
            const int i = firstUnit + u;
            hessian.row(i).setZero();
            hessian.col(i).setZero();
            hessian(i, i) = 1.0;
            rhs(i) = 0.0;
        }
    }
}

}  // namespace vision::aam
