// dlib's detector and shape predictor as the AAM fit's peer (dlib_peer.hpp).
#include "dlib_peer.hpp"

#include <dlib/image_processing.h>
#include <dlib/image_processing/frontal_face_detector.h>
#include <dlib/opencv/cv_image.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace mirror_eval {

struct DlibPeer::Impl {
    dlib::frontal_face_detector detector = dlib::get_frontal_face_detector();
    dlib::shape_predictor predictor;
    int upsample = 0;
};

DlibPeer::DlibPeer(const std::string& predictorPath, int upsample) : impl_(std::make_unique<Impl>())
{
    if (!std::filesystem::exists(predictorPath))
        throw std::runtime_error("dlib shape predictor " + predictorPath +
                                 ": no such file (Debian package libdlib-data)");
    try {
        dlib::deserialize(predictorPath) >> impl_->predictor;
    } catch (const std::exception& e) {
        throw std::runtime_error("dlib shape predictor " + predictorPath + ": cannot read it");
    }
    impl_->upsample = upsample;
}

DlibPeer::~DlibPeer() = default;

std::vector<FaceBoxPx> DlibPeer::detect(const cv::Mat& grey)
{
    const dlib::cv_image<unsigned char> image(grey);
    std::vector<dlib::rectangle> found;
    if (impl_->upsample == 0) {
        found = impl_->detector(image);
    } else {
        dlib::array2d<unsigned char> big;
        dlib::assign_image(big, image);
        for (int i = 0; i < impl_->upsample; ++i)
            dlib::pyramid_up(big);
        found = impl_->detector(big);
        const double shrink = std::pow(2.0, -impl_->upsample);
        for (dlib::rectangle& r : found)
            r = dlib::rectangle(
                static_cast<long>(r.left() * shrink), static_cast<long>(r.top() * shrink),
                static_cast<long>(r.right() * shrink), static_cast<long>(r.bottom() * shrink));
    }
    std::vector<FaceBoxPx> boxes;
    for (const dlib::rectangle& r : found)
        boxes.push_back({static_cast<double>(r.left()), static_cast<double>(r.top()),
                         static_cast<double>(r.right()), static_cast<double>(r.bottom())});
    return boxes;
}

std::optional<FaceBoxPx> DlibPeer::detectNear(const cv::Mat& grey, const FaceBoxPx& truthBox,
                                              double minIou)
{
    std::optional<FaceBoxPx> best;
    double bestIou = minIou;
    for (const FaceBoxPx& b : detect(grey)) {
        const double o = iou(b, truthBox);
        if (o >= bestIou)
            best = b, bestIou = o;
    }
    return best;
}

std::vector<Eigen::Vector2d> DlibPeer::landmarks(const cv::Mat& grey, const FaceBoxPx& box)
{
    const dlib::cv_image<unsigned char> image(grey);
    const dlib::full_object_detection shape =
        impl_->predictor(image, dlib::rectangle(std::lround(box.left), std::lround(box.top),
                                                std::lround(box.right), std::lround(box.bottom)));
    std::vector<Eigen::Vector2d> points;
    for (unsigned long i = 0; i < shape.num_parts(); ++i)
        points.emplace_back(static_cast<double>(shape.part(i).x()),
                            static_cast<double>(shape.part(i).y()));
    return points;
}

double iou(const FaceBoxPx& a, const FaceBoxPx& b) noexcept
{
    const double w = std::min(a.right, b.right) - std::max(a.left, b.left);
    const double h = std::min(a.bottom, b.bottom) - std::max(a.top, b.top);
    if (w <= 0 || h <= 0)
        return 0;
    const double inter = w * h;
    return inter / (a.width() * a.height() + b.width() * b.height() - inter);
}

FaceBoxPx boundingBoxOf(const std::vector<Eigen::Vector2d>& points)
{
    FaceBoxPx b{points.front().x(), points.front().y(), points.front().x(), points.front().y()};
    for (const auto& p : points) {
        b.left = std::min(b.left, p.x()), b.top = std::min(b.top, p.y());
        b.right = std::max(b.right, p.x()), b.bottom = std::max(b.bottom, p.y());
    }
    return b;
}

}  // namespace mirror_eval
