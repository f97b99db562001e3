// Mirrored training images (mirrored_training.hpp).
#include "mirrored_training.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace aam {

namespace {

constexpr float kSame = 1e-4f;  // CANDIDE units: the file's coordinates have three decimals

/// What unit `u` moves vertex `v` by (zero when it does not move it).
Eigen::Vector3f displacementOf(const vision::CandideUnit& u, int v)
{
    Eigen::Vector3f d = Eigen::Vector3f::Zero();
    for (std::size_t k = 0; k < u.vertices.size(); ++k)
        if (u.vertices[k] == v)
            d += u.displacements[k];
    return d;
}

bool mirrors(const Eigen::Vector3f& a, const Eigen::Vector3f& b)
{
    return std::abs(a.x() + b.x()) < kSame && std::abs(a.y() - b.y()) < kSame &&
           std::abs(a.z() - b.z()) < kSame;
}

/// How far the units' moves of `a` and `b` are from mirror images of each other.
float unitMismatch(const vision::CandideMesh& face, int a, int b)
{
    float sum = 0.f;
    for (const auto* list : {&face.shapeUnits, &face.animationUnits}) {
        for (const vision::CandideUnit& u : *list) {
            const Eigen::Vector3f da = displacementOf(u, a), db = displacementOf(u, b);
            sum += (Eigen::Vector3f(-da.x(), da.y(), da.z()) - db).norm();
        }
    }
    return sum;
}

}  // namespace

std::vector<int> mirrorPartners(const vision::CandideMesh& face)
{
    const int n = static_cast<int>(face.vertices.size());
    std::vector<int> partners(static_cast<std::size_t>(n), -1);
    for (int a = 0; a < n; ++a) {
        float best = 0.f;
        for (int b = 0; b < n; ++b) {
            if (!mirrors(face.vertices[static_cast<std::size_t>(a)],
                         face.vertices[static_cast<std::size_t>(b)]))
                continue;
            const float mismatch = unitMismatch(face, a, b);
            if (partners[static_cast<std::size_t>(a)] < 0 || mismatch < best) {
                partners[static_cast<std::size_t>(a)] = b;
                best = mismatch;
            }
        }
        if (partners[static_cast<std::size_t>(a)] < 0)
            throw std::invalid_argument(
                "mirrored training: CANDIDE vertex " +
                std::to_string(face.candideNumber[static_cast<std::size_t>(a)]) +
                " has no mirror partner");
    }
    return partners;
}

Shape2d mirroredShape(const Shape2d& shape, const std::vector<int>& partners, int width)
{
    Shape2d out(shape.size());
    for (std::size_t v = 0; v < shape.size(); ++v) {
        const Eigen::Vector2d& p = shape[static_cast<std::size_t>(partners[v])];
        out[v] = {static_cast<double>(width - 1) - p.x(), p.y()};
    }
    return out;
}

cv::Mat mirroredImage(const cv::Mat& grey)
{
    cv::Mat out;
    cv::flip(grey, out, 1);
    return out;
}

}  // namespace aam
