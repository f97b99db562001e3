// The CANDIDE head's projection and its Jacobian (§5; dissertation eqs. 81, 84, 86). The text's
// projection is orthographic with a scale (1 + f); ours is the same with the scale itself as the
// parameter (image pixels per CANDIDE unit), and CANDIDE's y (up) flipped into the image's y
// (down), with the roll applied in the image as the builder's fit does (tools/aam/candide_fit).
#include "aam_head_projection.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace vision::aam {

namespace {

using UnitVector = Eigen::Matrix<float, kAamShapeUnits + kAamAnimationUnits, 1>;

UnitVector unitParameters(const AamHead& head) noexcept
{
    UnitVector u;
    for (int i = 0; i < kAamShapeUnits; ++i)
        u(i) = head.sigma[static_cast<std::size_t>(i)];
    for (int i = 0; i < kAamAnimationUnits; ++i)
        u(kAamShapeUnits + i) = head.tau[static_cast<std::size_t>(i)];
    return u;
}

Eigen::Matrix3f pitchMatrix(float angle, bool derivative) noexcept
{
    const float c = std::cos(angle), s = std::sin(angle);
    Eigen::Matrix3f m;
    if (derivative)
        m << 0, 0, 0, 0, -s, -c, 0, c, -s;
    else
        m << 1, 0, 0, 0, c, -s, 0, s, c;
    return m;
}

Eigen::Matrix3f yawMatrix(float angle, bool derivative) noexcept
{
    const float c = std::cos(angle), s = std::sin(angle);
    Eigen::Matrix3f m;
    if (derivative)
        m << -s, 0, c, 0, 0, 0, -c, 0, -s;
    else
        m << c, 0, s, 0, 1, 0, -s, 0, c;
    return m;
}

}  // namespace

Eigen::Matrix<float, kHeadParameters, 1> headParameters(const AamHead& head) noexcept
{
    Eigen::Matrix<float, kHeadParameters, 1> r;
    r.head<6>() << head.scale, head.roll, head.pitch, head.yaw, head.translation.x,
        head.translation.y;
    r.tail<kAamShapeUnits + kAamAnimationUnits>() = unitParameters(head);
    return r;
}

void setHeadParameters(AamHead& head, const Eigen::Matrix<float, kHeadParameters, 1>& r) noexcept
{
    head.scale = r(0);
    head.roll = r(1);
    head.pitch = r(2);
    head.yaw = r(3);
    head.translation = {r(4), r(5)};
    for (int i = 0; i < kAamShapeUnits; ++i)
        head.sigma[static_cast<std::size_t>(i)] = r(6 + i);
    for (int i = 0; i < kAamAnimationUnits; ++i)
        head.tau[static_cast<std::size_t>(i)] = r(6 + kAamShapeUnits + i);
}

void projectHead(const Tables& t, const AamHead& head, float* points,
                 HeadJacobian* jacobian) noexcept
{
    const UnitVector units = unitParameters(head);
    const float c = std::cos(head.roll), s = std::sin(head.roll);
    // Roll(roll) * Flip: the image's 2x3 projection of a turned model point.
    Eigen::Matrix<float, 2, 3> rollFlip;
    rollFlip << c, s, 0, s, -c, 0;
    const Eigen::Matrix3f pitch = pitchMatrix(head.pitch, false);
    const Eigen::Matrix3f yaw = yawMatrix(head.yaw, false);
    const Eigen::Matrix3f turn = pitch * yaw;
    const Eigen::Matrix<float, 2, 3> project = head.scale * rollFlip * turn;
    const Eigen::Matrix<float, 2, 3> byPitch =
        head.scale * rollFlip * pitchMatrix(head.pitch, true) * yaw;
    const Eigen::Matrix<float, 2, 3> byYaw =
        head.scale * rollFlip * pitch * yawMatrix(head.yaw, true);
    const Eigen::Vector2f translation(head.translation.x, head.translation.y);
    for (int v = 0; v < t.vertices; ++v) {
        const auto& unitsOfV = t.headUnits[static_cast<std::size_t>(v)];
        const Eigen::Vector3f g = t.headVertices[static_cast<std::size_t>(v)] + unitsOfV * units;
        const Eigen::Vector2f m = rollFlip * (turn * g);
        const Eigen::Vector2f point = translation + head.scale * m;
        points[2 * v] = point.x();
        points[2 * v + 1] = point.y();
        if (jacobian == nullptr)
            continue;
        HeadJacobian& j = jacobian[v];
        j.col(0) = m;
        j.col(1) << -head.scale * m.y(), head.scale * m.x();
        j.col(2) = byPitch * g;
        j.col(3) = byYaw * g;
        j.col(4) << 1.f, 0.f;
        j.col(5) << 0.f, 1.f;
        j.rightCols<kAamShapeUnits + kAamAnimationUnits>().noalias() = project * unitsOfV;
    }
}

void placeHeadOn(const Tables& t, const float* shape, AamHead& head) noexcept
{
    // image = t + (a x + b y', b x - a y') with (x, y') the model point turned by the head's yaw
    // (0 for a frontal start): linear in (tx, ty, a, b), as the builder's similarity solve.
    head.pitch = 0.f;
    const Eigen::Matrix3f yaw = yawMatrix(head.yaw, false);
    const UnitVector units = unitParameters(head);
    Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
    Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
    for (int v = 0; v < t.vertices; ++v) {
        const Eigen::Vector3f g = yaw * (t.headVertices[static_cast<std::size_t>(v)] +
                                         t.headUnits[static_cast<std::size_t>(v)] * units);
        Eigen::Matrix<double, 2, 4> row;
        row << 1, 0, g.x(), g.y(), 0, 1, -g.y(), g.x();
        normal.noalias() += row.transpose() * row;
        rhs.noalias() += row.transpose() * Eigen::Vector2d(shape[2 * v], shape[2 * v + 1]);
    }
    const Eigen::Vector4d x = normal.ldlt().solve(rhs);
    head.translation = {static_cast<float>(x(0)), static_cast<float>(x(1))};
    head.scale = static_cast<float>(std::hypot(x(2), x(3)));
    head.roll = static_cast<float>(std::atan2(x(3), x(2)));
}

}  // namespace vision::aam
