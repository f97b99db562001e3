// Pictures for checking tables and fits by eye (OpenCV drawing, offline only).
#include "annotation_drawing.hpp"

#include <opencv2/imgproc.hpp>

namespace aam {

namespace {
cv::Point pixel(const Eigen::Vector2d& p)
{
    return {cvRound(p.x()), cvRound(p.y())};
}
}  // namespace

cv::Mat closeUp(const cv::Mat& image, std::vector<std::vector<Eigen::Vector2d>*> points, int height)
{
    Eigen::Vector2d low(1e30, 1e30), high(-1e30, -1e30);
    for (const auto* set : points) {
        for (const auto& p : *set) {
            low = low.cwiseMin(p);
            high = high.cwiseMax(p);
        }
    }
    const Eigen::Vector2d margin = 0.1 * (high - low);
    const cv::Rect box = cv::Rect(pixel(low - margin), pixel(high + margin)) &
                         cv::Rect(0, 0, image.cols, image.rows);
    const double scale = static_cast<double>(height) / box.height;
    cv::Mat out;
    cv::resize(image(box), out, {}, scale, scale, cv::INTER_CUBIC);
    for (auto* set : points) {
        for (auto& p : *set)
            p = (p - Eigen::Vector2d(box.x, box.y)) * scale;
    }
    return out;
}

void drawNumberedPoints(cv::Mat& image, const std::vector<Eigen::Vector2d>& points,
                        const std::vector<std::string>& labels)
{
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::string text = i < labels.size() ? labels[i] : std::to_string(i);
        cv::circle(image, pixel(points[i]), 2, {0, 255, 255}, cv::FILLED, cv::LINE_AA);
        if (text.empty())
            continue;
        cv::putText(image, text, pixel(points[i]) + cv::Point(3, -3), cv::FONT_HERSHEY_PLAIN, 1.0,
                    {0, 255, 255}, 1, cv::LINE_AA);
    }
}

void drawMesh(cv::Mat& image, const vision::CandideMesh& mesh,
              const std::vector<Eigen::Vector2d>& projected)
{
    for (const auto& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            cv::line(image, pixel(projected[static_cast<std::size_t>(t[k])]),
                     pixel(projected[static_cast<std::size_t>(t[(k + 1) % 3])]), {0, 200, 0}, 1,
                     cv::LINE_AA);
        }
    }
    for (const auto& p : projected)
        cv::circle(image, pixel(p), 1, {0, 0, 255}, cv::FILLED);
}

}  // namespace aam
