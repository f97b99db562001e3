#include "platform/image_file.hpp"

#include "image_header.hpp"
#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace platform {

vision::ImageBuffer loadImageFile(const std::string& path, const char* what)
{
    const std::string prefix = std::string(what) + " " + path + ": ";
    const vision::BoundedFile file = vision::readBoundedFile(path, vision::limits::kImageFileBytes);
    if (file.status == vision::BoundedFile::Status::Missing)
        throw std::runtime_error(prefix + "no such file");
    if (file.status != vision::BoundedFile::Status::Ok)
        throw std::runtime_error(prefix + file.problem);
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(file.text.data());
    // From the header, before the decoder allocates: a small file can claim gigapixels.
    if (const std::string wrong = checkImageHeader(bytes, file.text.size()); !wrong.empty())
        throw std::runtime_error(prefix + wrong);

    cv::Mat bgr;
    try {
        const cv::Mat encoded(1, static_cast<int>(file.text.size()), CV_8UC1,
                              const_cast<std::uint8_t*>(bytes));
        bgr = cv::imdecode(encoded, cv::IMREAD_COLOR);
    } catch (const cv::Exception& e) {
        throw std::runtime_error(prefix + "not an image OpenCV can read (" + e.err + ")");
    }
    if (bgr.empty() || bgr.type() != CV_8UC3)
        throw std::runtime_error(prefix + "not an image OpenCV can read");

    vision::ImageBuffer rgb(bgr.cols, bgr.rows, vision::PixelFormat::RGB24);
    const vision::ImageView view = rgb.view();
    // Convert straight into the buffer (its padded stride) instead of through another Mat.
    cv::Mat target(view.height, view.width, CV_8UC3, view.data,
                   static_cast<std::size_t>(view.stride));
    cv::cvtColor(bgr, target, cv::COLOR_BGR2RGB);
    return rgb;
}

}  // namespace platform
