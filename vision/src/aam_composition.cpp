// The inverse compositional update of the 2D shape (§5, 5.3.2; Matthews & Baker's composition of
// N o W with an increment's inverse, vertex by vertex, averaged over each vertex's triangles).
#include "aam_composition.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace vision::aam {

Similarity similarityOf(const Tables& t, const float* q) noexcept
{
    const float a = q[0] / t.similarityNorm, b = q[1] / t.similarityNorm;
    const float unit = 1.f / std::sqrt(static_cast<float>(t.vertices));
    Similarity n;
    n.linear << 1.f + a, -b, b, 1.f + a;
    n.translation << q[2] * unit, q[3] * unit;
    return n;
}

void parametersOf(const Tables& t, const Similarity& n, float* q) noexcept
{
    const float root = std::sqrt(static_cast<float>(t.vertices));
    q[0] = (0.5f * (n.linear(0, 0) + n.linear(1, 1)) - 1.f) * t.similarityNorm;
    q[1] = 0.5f * (n.linear(1, 0) - n.linear(0, 1)) * t.similarityNorm;
    q[2] = n.translation.x() * root;
    q[3] = n.translation.y() * root;
}

void shapeFromParameters(const Tables& t, const float* q, const float* p, float* shape) noexcept
{
    const Similarity n = similarityOf(t, q);
    for (int v = 0; v < t.vertices; ++v) {
        Eigen::Vector2f x = t.meanShape.segment<2>(2 * v);
        for (int j = 0; j < t.shapeModeCount; ++j)
            x += p[j] * t.shapeModes.col(j).segment<2>(2 * v);
        const Eigen::Vector2f image = t.centre + n.linear * (x - t.centre) + n.translation;
        shape[2 * v] = image.x();
        shape[2 * v + 1] = image.y();
    }
}

void vertexAffines(const Tables& t, const TriangleAffine* triangles,
                   TriangleAffine* vertices) noexcept
{
    for (int v = 0; v < t.vertices; ++v) {
        const int first = t.vertexTriangleStart[static_cast<std::size_t>(v)];
        const int end = t.vertexTriangleStart[static_cast<std::size_t>(v) + 1];
        TriangleAffine mean;
        mean.linear.setZero();
        for (int k = first; k < end; ++k) {
            const TriangleAffine& a = triangles[t.vertexTriangles[static_cast<std::size_t>(k)]];
            mean.linear += a.linear;
            mean.offset += a.offset;
        }
        const float inverse = 1.f / static_cast<float>(end - first);
        mean.linear *= inverse;
        mean.offset *= inverse;
        vertices[v] = mean;
    }
}

void composeInverse(const Tables& t, const TriangleAffine* vertexMaps, const float* dq,
                    const float* dp, float* q, float* p, float* shape) noexcept
{
    // The composed shape, s-dagger, into `shape`.
    for (int v = 0; v < t.vertices; ++v) {
        Eigen::Vector2f x = t.meanShape.segment<2>(2 * v);
        for (int i = 0; i < 4; ++i)
            x -= dq[i] * t.similarity.col(i).segment<2>(2 * v);
        for (int j = 0; j < t.shapeModeCount; ++j)
            x -= dp[j] * t.shapeModes.col(j).segment<2>(2 * v);
        const Eigen::Vector2f image = vertexMaps[v].linear * x + vertexMaps[v].offset;
        shape[2 * v] = image.x();
        shape[2 * v + 1] = image.y();
    }
    decomposeShape(t, q, p, shape);
}

void decomposeShape(const Tables& t, float* q, float* p, float* shape) noexcept
{
    // q: s-dagger less s0 on the similarity basis (exact: the modes are orthogonal to it).
    for (int i = 0; i < 4; ++i) {
        float sum = 0.f;
        for (int k = 0; k < 2 * t.vertices; ++k)
            sum += t.similarity(k, i) * (shape[k] - t.meanShape(k));
        q[i] = sum;
    }
    // p: N^-1(s-dagger) less s0 on the modes, within +-3 standard deviations.
    const Similarity n = similarityOf(t, q);
    const Eigen::Matrix2f back = n.linear.inverse();
    for (int j = 0; j < t.shapeModeCount; ++j)
        p[j] = 0.f;
    for (int v = 0; v < t.vertices; ++v) {
        const Eigen::Vector2f image(shape[2 * v], shape[2 * v + 1]);
        const Eigen::Vector2f x = t.centre + back * (image - t.centre - n.translation);
        const Eigen::Vector2f d = x - t.meanShape.segment<2>(2 * v);
        for (int j = 0; j < t.shapeModeCount; ++j)
            p[j] += t.shapeModes.col(j).segment<2>(2 * v).dot(d);
    }
    for (int j = 0; j < t.shapeModeCount; ++j) {
        const float limit = t.shapeLimits[static_cast<std::size_t>(j)];
        p[j] = std::clamp(p[j], -limit, limit);
    }
    shapeFromParameters(t, q, p, shape);
}

}  // namespace vision::aam
