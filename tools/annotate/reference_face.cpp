#include "reference_face.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace annotate {

ReferenceFace::ReferenceFace(const vision::CandideMesh& face, const aam::AnnotationScheme& scheme,
                             int size)
    : size_(size), face_(face)
{
    // CANDIDE frontal, orthographic: x to the person's left is image right, y up is image up.
    float x0 = 1e9f, x1 = -1e9f, y0 = 1e9f, y1 = -1e9f;
    for (const Eigen::Vector3f& v : face.vertices) {
        x0 = std::min(x0, v.x()), x1 = std::max(x1, v.x());
        y0 = std::min(y0, v.y()), y1 = std::max(y1, v.y());
    }
    const double scale = 0.86 * size / std::max(x1 - x0, y1 - y0);
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    for (const Eigen::Vector3f& v : face.vertices)
        vertices_.emplace_back(0.5 * size + scale * (v.x() - cx),
                               0.5 * size - scale * (v.y() - cy));

    points_.assign(static_cast<std::size_t>(scheme.pointCount), Eigen::Vector2d::Zero());
    mapped_.assign(points_.size(), false);
    for (const aam::SchemeRow& row : scheme.rows) {
        const int v = face.indexOfCandideVertex(row.candideVertex);
        if (v < 0)
            continue;
        for (const int p : row.at.points) {
            if (p < 0 || p >= scheme.pointCount || mapped_[static_cast<std::size_t>(p)])
                continue;
            points_[static_cast<std::size_t>(p)] = vertices_[static_cast<std::size_t>(v)];
            mapped_[static_cast<std::size_t>(p)] = true;
        }
    }
    if (std::none_of(mapped_.begin(), mapped_.end(), [](bool m) { return m; }))
        throw std::invalid_argument("no point of the " + std::string(scheme.name) +
                                    " scheme lies on this CANDIDE mesh");
    // The rest between their mapped neighbours in the scheme's order.
    const int n = scheme.pointCount;
    for (int i = 0; i < n; ++i) {
        if (mapped_[static_cast<std::size_t>(i)])
            continue;
        int before = i - 1, after = i + 1;
        while (before >= 0 && !mapped_[static_cast<std::size_t>(before)])
            --before;
        while (after < n && !mapped_[static_cast<std::size_t>(after)])
            ++after;
        if (before < 0)
            points_[static_cast<std::size_t>(i)] = points_[static_cast<std::size_t>(after)];
        else if (after >= n)
            points_[static_cast<std::size_t>(i)] = points_[static_cast<std::size_t>(before)];
        else {
            const double t = static_cast<double>(i - before) / (after - before);
            points_[static_cast<std::size_t>(i)] =
                (1 - t) * points_[static_cast<std::size_t>(before)] +
                t * points_[static_cast<std::size_t>(after)];
        }
    }
}

cv::Mat ReferenceFace::draw(int placed, int next) const
{
    cv::Mat picture(size_, size_, CV_8UC3, cv::Scalar(40, 40, 40));
    const auto at = [](const Eigen::Vector2d& p) {
        return cv::Point(static_cast<int>(p.x() + 0.5), static_cast<int>(p.y() + 0.5));
    };
    for (const auto& t : face_.triangles)
        for (int k = 0; k < 3; ++k)
            cv::line(
                picture, at(vertices_[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])]),
                at(vertices_[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])]),
                cv::Scalar(110, 110, 110), 1, cv::LINE_AA);
    for (int i = 0; i < pointCount(); ++i) {
        const cv::Scalar colour = i < placed ? cv::Scalar(60, 200, 60) : cv::Scalar(200, 200, 200);
        cv::circle(picture, at(points_[static_cast<std::size_t>(i)]), 3, colour, cv::FILLED,
                   cv::LINE_AA);
    }
    if (next >= 0 && next < pointCount()) {
        const cv::Point p = at(points_[static_cast<std::size_t>(next)]);
        cv::circle(picture, p, 9, cv::Scalar(40, 40, 240), 2, cv::LINE_AA);
        cv::putText(picture, std::to_string(next + 1), p + cv::Point(11, -8),
                    cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(40, 40, 240), 2, cv::LINE_AA);
    }
    return picture;
}

}  // namespace annotate
