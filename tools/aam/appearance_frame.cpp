// The appearance frame: s0 scaled into it, then each triangle's bounding box scanned for the
// pixels inside it (barycentric coordinates all >= 0).
#include "appearance_frame.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aam {

namespace {

constexpr double kInside = -1e-9;  // a pixel exactly on an edge is inside

/// Barycentric coordinates of p in triangle (a, b, c), or nothing for a triangle without area.
bool barycentricIn(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& p, Eigen::Vector3d& out)
{
    Eigen::Matrix2d m;
    m << b - a, c - a;
    const double det = m.determinant();
    if (std::abs(det) < 1e-12)
        return false;
    const Eigen::Vector2d uv = m.inverse() * (p - a);
    out = {1 - uv.x() - uv.y(), uv.x(), uv.y()};
    return true;
}

void placeMean(AppearanceFrame& frame, const Shape2d& mean, int width)
{
    Eigen::Vector2d high = mean.front();
    frame.low = mean.front();
    for (const auto& p : mean) {
        frame.low = frame.low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    frame.scale =
        (width - 3) / (high.x() - frame.low.x());  // a pixel's margin each side, x = 1 .. width - 2
    frame.width = width;
    frame.height = static_cast<int>(std::ceil((high.y() - frame.low.y()) * frame.scale)) + 3;
    for (const auto& p : mean)
        frame.meanShape.push_back(frame.toFrame(p));
}

}  // namespace

AppearanceFrame appearanceFrame(const vision::CandideMesh& face, const Shape2d& mean, int width)
{
    if (width < 16 || width > 1024) {
        throw std::invalid_argument("appearance frame: width " + std::to_string(width) +
                                    " is not in [16, 1024]");
    }
    AppearanceFrame frame;
    placeMean(frame, mean, width);
    std::vector<int> owner(static_cast<std::size_t>(frame.width * frame.height), -1);
    std::vector<Eigen::Vector3d> weights(owner.size());
    for (std::size_t t = 0; t < face.triangles.size(); ++t) {
        const auto& tri = face.triangles[t];
        const Eigen::Vector2d& a = frame.meanShape[static_cast<std::size_t>(tri[0])];
        const Eigen::Vector2d& b = frame.meanShape[static_cast<std::size_t>(tri[1])];
        const Eigen::Vector2d& c = frame.meanShape[static_cast<std::size_t>(tri[2])];
        const Eigen::Vector2d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
        for (int y = static_cast<int>(std::ceil(lo.y())); y <= static_cast<int>(std::floor(hi.y()));
             ++y) {
            for (int x = static_cast<int>(std::ceil(lo.x()));
                 x <= static_cast<int>(std::floor(hi.x())); ++x) {
                const auto at = static_cast<std::size_t>(y * frame.width + x);
                Eigen::Vector3d w;
                if (owner[at] >= 0 || !barycentricIn(a, b, c, Eigen::Vector2d(x, y), w) ||
                    w.minCoeff() < kInside)
                    continue;
                owner[at] = static_cast<int>(t);
                weights[at] = w;
            }
        }
    }
    for (std::size_t at = 0; at < owner.size(); ++at) {
        if (owner[at] < 0)
            continue;
        frame.pixels.push_back({static_cast<int>(at) % frame.width,
                                static_cast<int>(at) / frame.width, owner[at], weights[at]});
    }
    return frame;
}

}  // namespace aam
