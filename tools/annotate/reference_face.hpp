#pragma once
// The picture `aam-annotate` prompts with (dissertation 5.3.1: the annotation tool shows which
// point to click next): CANDIDE-3's face drawn frontal, and where on it each point of an
// annotation scheme lies. A point the scheme maps to a CANDIDE vertex is drawn on that vertex (a
// point that is half of a two-point mean, on its vertex too); a point without a vertex (pupils,
// points between vertices) between the nearest mapped points before and after it in the scheme's
// order, which run along the same contour.

#include "annotation_schemes.hpp"
#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace annotate {

class ReferenceFace {
public:
    /// `face`: the CANDIDE mesh the scheme's table refers to (kept). Throws std::invalid_argument
    /// when no point of the scheme maps onto it.
    ReferenceFace(const vision::CandideMesh& face, const aam::AnnotationScheme& scheme,
                  int size = 480);

    int pointCount() const noexcept { return static_cast<int>(points_.size()); }
    /// Where scheme point `i` lies on the drawing (pixels).
    const Eigen::Vector2d& point(int i) const { return points_.at(static_cast<std::size_t>(i)); }
    /// Whether the scheme maps point `i` to a CANDIDE vertex (else it was placed between two).
    bool mapped(int i) const { return mapped_.at(static_cast<std::size_t>(i)); }

    /// The mesh in grey, the points `placed` so far in green, point `next` as a red ring with its
    /// number (none when `next` is past the last).
    cv::Mat draw(int placed, int next) const;

private:
    int size_;
    std::vector<Eigen::Vector2d> vertices_;  ///< the mesh's vertices on the drawing
    const vision::CandideMesh& face_;
    std::vector<Eigen::Vector2d> points_;
    std::vector<bool> mapped_;
};

}  // namespace annotate
