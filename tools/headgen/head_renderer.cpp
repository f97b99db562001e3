// A textured CANDIDE head drawn by triangles (§5's mesh; the texture is a photograph's 5.3.1 fit).
//
// Facing: a triangle faces the camera when its posed image has the winding it has in the frontal
// texture photograph (CANDIDE's windings are not all alike, the photograph's view is frontal, so
// this needs no normals). Order: by mean depth, far first, into a triangle-index image; every
// pixel then samples the photograph through its triangle's affine map.
#include "head_renderer.hpp"

#include <algorithm>
#include <numeric>
#include <opencv2/imgproc.hpp>

namespace headgen {

namespace {

double signedArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
{
    return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

/// Triangles facing the camera, far first.
std::vector<int> visibleTriangles(const vision::CandideMesh& mesh, const HeadTexture& texture,
                                  const ProjectedHead& head)
{
    std::vector<int> shown;
    std::vector<double> depth(mesh.triangles.size(), 0.0);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& [i, j, k] = mesh.triangles[t];
        const auto at = [](const std::vector<Eigen::Vector2d>& p, int n) {
            return p[static_cast<std::size_t>(n)];
        };
        const double frontal = signedArea(at(texture.uv, i), at(texture.uv, j), at(texture.uv, k));
        const double posed = signedArea(at(head.image, i), at(head.image, j), at(head.image, k));
        if (std::abs(frontal) < 1e-6 || frontal * posed <= 0)
            continue;
        depth[t] = head.depth[static_cast<std::size_t>(i)] +
                   head.depth[static_cast<std::size_t>(j)] +
                   head.depth[static_cast<std::size_t>(k)];
        shown.push_back(static_cast<int>(t));
    }
    std::stable_sort(shown.begin(), shown.end(), [&](int a, int b) {
        return depth[static_cast<std::size_t>(a)] < depth[static_cast<std::size_t>(b)];
    });
    return shown;
}

/// The affine map from the posed triangle (ROI coordinates) to the photograph, 2x3 CV_64F.
cv::Mat posedToPhoto(const std::array<int, 3>& tri, const std::vector<Eigen::Vector2d>& posed,
                     const std::vector<Eigen::Vector2d>& uv, cv::Point2d origin)
{
    cv::Point2f from[3], to[3];
    for (int n = 0; n < 3; ++n) {
        const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(n)]);
        from[n] = cv::Point2f(static_cast<float>(posed[v].x() - origin.x),
                              static_cast<float>(posed[v].y() - origin.y));
        to[n] = cv::Point2f(static_cast<float>(uv[v].x()), static_cast<float>(uv[v].y()));
    }
    return cv::getAffineTransform(from, to);
}

/// Depth of triangle `tri` at image point p (barycentric).
double depthAt(const std::array<int, 3>& tri, const ProjectedHead& head, const Eigen::Vector2d& p)
{
    const auto v = [&](int n) {
        return static_cast<std::size_t>(tri[static_cast<std::size_t>(n)]);
    };
    const double all = signedArea(head.image[v(0)], head.image[v(1)], head.image[v(2)]);
    if (std::abs(all) < 1e-9)
        return head.depth[v(0)];
    const double w0 = signedArea(p, head.image[v(1)], head.image[v(2)]) / all;
    const double w1 = signedArea(head.image[v(0)], p, head.image[v(2)]) / all;
    return w0 * head.depth[v(0)] + w1 * head.depth[v(1)] + (1 - w0 - w1) * head.depth[v(2)];
}

bool usesVertex(const std::array<int, 3>& tri, int vertex)
{
    return tri[0] == vertex || tri[1] == vertex || tri[2] == vertex;
}

/// A vertex is seen when the triangle drawn at (or next to) it uses it, or lies no nearer there.
std::vector<bool> seenVertices(const vision::CandideMesh& mesh, const ProjectedHead& head,
                               const cv::Mat& ids, cv::Point origin)
{
    constexpr double kDepthTolerance = 0.02;  // model units: a vertex on the drawn surface
    std::vector<bool> seen(head.image.size(), false);
    for (std::size_t v = 0; v < head.image.size(); ++v) {
        const Eigen::Vector2d& p = head.image[v];
        const int cx = static_cast<int>(std::lround(p.x())) - origin.x;
        const int cy = static_cast<int>(std::lround(p.y())) - origin.y;
        for (int dy = -1; dy <= 1 && !seen[v]; ++dy) {
            for (int dx = -1; dx <= 1 && !seen[v]; ++dx) {
                const int x = cx + dx, y = cy + dy;
                if (x < 0 || y < 0 || x >= ids.cols || y >= ids.rows)
                    continue;
                const int t = ids.at<int>(y, x);
                if (t < 0)
                    continue;
                const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
                seen[v] = usesVertex(tri, static_cast<int>(v)) ||
                          depthAt(tri, head, p) <= head.depth[v] + kDepthTolerance;
            }
        }
    }
    return seen;
}

}  // namespace

std::vector<bool> drawHead(cv::Mat& frame, const vision::CandideMesh& mesh,
                           const HeadTexture& texture, const ProjectedHead& head)
{
    double x0 = head.image[0].x(), y0 = head.image[0].y(), x1 = x0, y1 = y0;
    for (const auto& p : head.image) {
        x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y());
        x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
    }
    const cv::Rect roi = cv::Rect(cv::Point(static_cast<int>(x0) - 2, static_cast<int>(y0) - 2),
                                  cv::Point(static_cast<int>(x1) + 3, static_cast<int>(y1) + 3)) &
                         cv::Rect(0, 0, frame.cols, frame.rows);
    if (roi.area() == 0)
        return std::vector<bool>(head.image.size(), false);
    const cv::Point2d origin(roi.x, roi.y);

    // Triangle index per pixel, far triangles overdrawn by near ones (4 bits of sub-pixel).
    cv::Mat ids(roi.size(), CV_32S, cv::Scalar(-1));
    std::vector<cv::Mat> maps(mesh.triangles.size());
    for (int t : visibleTriangles(mesh, texture, head)) {
        const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
        cv::Point corners[3];
        for (int n = 0; n < 3; ++n) {
            const auto& p = head.image[static_cast<std::size_t>(tri[static_cast<std::size_t>(n)])];
            corners[n] = cv::Point(static_cast<int>(std::lround((p.x() - origin.x) * 16)),
                                   static_cast<int>(std::lround((p.y() - origin.y) * 16)));
        }
        cv::fillConvexPoly(ids, corners, 3, cv::Scalar(t), cv::LINE_8, 4);
        maps[static_cast<std::size_t>(t)] = posedToPhoto(tri, head.image, texture.uv, origin);
    }

    // Every covered pixel samples the photograph through its triangle's map.
    cv::Mat mapX(roi.size(), CV_32F, cv::Scalar(-1)), mapY(roi.size(), CV_32F, cv::Scalar(-1));
    cv::Mat cover(roi.size(), CV_32F, cv::Scalar(0));
    for (int y = 0; y < roi.height; ++y) {
        for (int x = 0; x < roi.width; ++x) {
            const int t = ids.at<int>(y, x);
            if (t < 0)
                continue;
            const cv::Mat& m = maps[static_cast<std::size_t>(t)];
            mapX.at<float>(y, x) = static_cast<float>(m.at<double>(0, 0) * x +
                                                      m.at<double>(0, 1) * y + m.at<double>(0, 2));
            mapY.at<float>(y, x) = static_cast<float>(m.at<double>(1, 0) * x +
                                                      m.at<double>(1, 1) * y + m.at<double>(1, 2));
            cover.at<float>(y, x) = 1.f;
        }
    }
    cv::Mat sampled;
    cv::remap(texture.photo, sampled, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    sampled.convertTo(sampled, CV_32FC3);

    // A soft outline: the coverage blurred inside the head only (outside, nothing was sampled).
    cv::Mat alpha;
    cv::GaussianBlur(cover, alpha, cv::Size(3, 3), 0.8);
    alpha = alpha.mul(cover);
    cv::Mat alpha3;
    cv::merge(std::vector<cv::Mat>{alpha, alpha, alpha}, alpha3);
    const cv::Mat blended = sampled.mul(alpha3) + frame(roi).mul(cv::Scalar::all(1.0) - alpha3);
    blended.copyTo(frame(roi));
    return seenVertices(mesh, head, ids, cv::Point(roi.x, roi.y));
}

}  // namespace headgen
