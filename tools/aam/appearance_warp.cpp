#include "appearance_warp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aam {

namespace {

double bilinear(const cv::Mat& grey, const Eigen::Vector2d& p)
{
    const double x = std::clamp(p.x(), 0.0, grey.cols - 1.0),
                 y = std::clamp(p.y(), 0.0, grey.rows - 1.0);
    const int x0 = std::min(static_cast<int>(x), grey.cols - 2 < 0 ? 0 : grey.cols - 2);
    const int y0 = std::min(static_cast<int>(y), grey.rows - 2 < 0 ? 0 : grey.rows - 2);
    const int x1 = std::min(x0 + 1, grey.cols - 1), y1 = std::min(y0 + 1, grey.rows - 1);
    const double fx = x - x0, fy = y - y0;
    const auto at = [&](int yy, int xx) {
        return static_cast<double>(grey.at<unsigned char>(yy, xx));
    };
    return (1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x1)) +
           fy * ((1 - fx) * at(y1, x0) + fx * at(y1, x1));
}

}  // namespace

Eigen::VectorXd warpToFrame(const cv::Mat& grey, const Shape2d& shape,
                            const vision::CandideMesh& face, const AppearanceFrame& frame)
{
    Eigen::VectorXd out(static_cast<Eigen::Index>(frame.pixels.size()));
    for (std::size_t i = 0; i < frame.pixels.size(); ++i) {
        const FramePixel& px = frame.pixels[i];
        const auto& tri = face.triangles[static_cast<std::size_t>(px.triangle)];
        const Eigen::Vector2d place = px.barycentric(0) * shape[static_cast<std::size_t>(tri[0])] +
                                      px.barycentric(1) * shape[static_cast<std::size_t>(tri[1])] +
                                      px.barycentric(2) * shape[static_cast<std::size_t>(tri[2])];
        out(static_cast<Eigen::Index>(i)) = bilinear(grey, place);
    }
    return out;
}

cv::Mat frameImage(const AppearanceFrame& frame, const Eigen::VectorXd& values)
{
    cv::Mat image = cv::Mat::zeros(frame.height, frame.width, CV_64F);
    for (std::size_t i = 0; i < frame.pixels.size(); ++i) {
        image.at<double>(frame.pixels[i].y, frame.pixels[i].x) =
            values(static_cast<Eigen::Index>(i));
    }
    return image;
}

Eigen::VectorXd resampledTo(const AppearanceFrame& from, const Eigen::VectorXd& values,
                            const AppearanceFrame& to)
{
    const cv::Mat image = frameImage(from, values);
    cv::Mat inside = cv::Mat::zeros(from.height, from.width, CV_64F);
    for (const FramePixel& px : from.pixels)
        inside.at<double>(px.y, px.x) = 1;
    Eigen::VectorXd out(static_cast<Eigen::Index>(to.pixels.size()));
    for (std::size_t i = 0; i < to.pixels.size(); ++i) {
        // The same aligned-frame point in `from`'s pixels.
        const Eigen::Vector2d aligned =
            (Eigen::Vector2d(to.pixels[i].x, to.pixels[i].y) - Eigen::Vector2d(1, 1)) / to.scale +
            to.low;
        const Eigen::Vector2d p = from.toFrame(aligned);
        const int x0 = static_cast<int>(std::floor(p.x())),
                  y0 = static_cast<int>(std::floor(p.y()));
        double sum = 0, weight = 0;
        for (int dy = 0; dy <= 1; ++dy) {
            for (int dx = 0; dx <= 1; ++dx) {
                const int x = std::clamp(x0 + dx, 0, from.width - 1),
                          y = std::clamp(y0 + dy, 0, from.height - 1);
                if (inside.at<double>(y, x) == 0)
                    continue;
                const double w =
                    (dx ? p.x() - x0 : 1 - (p.x() - x0)) * (dy ? p.y() - y0 : 1 - (p.y() - y0));
                sum += w * image.at<double>(y, x);
                weight += w;
            }
        }
        out(static_cast<Eigen::Index>(i)) =
            weight > 1e-9 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
    }
    return out;
}

}  // namespace aam
