#include "platform/image_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace platform {

vision::ImageBuffer loadImageFile(const std::string& path, const char* what)
{
    const std::string prefix = std::string(what) + " " + path + ": ";
    // Checked first so the common mistakes get their own words; imread only says "empty".
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        const int error = errno;
        throw std::runtime_error(prefix + (error == ENOENT ? std::string("no such file")
                                                           : std::string(std::strerror(error))));
    }
    if (!S_ISREG(st.st_mode))
        throw std::runtime_error(prefix + "not a regular file");

    cv::Mat bgr;
    try {
        bgr = cv::imread(path, cv::IMREAD_COLOR);
    } catch (const cv::Exception& e) {
        throw std::runtime_error(prefix + "not an image OpenCV can read (" + e.err + ")");
    }
    if (bgr.empty() || bgr.type() != CV_8UC3)
        throw std::runtime_error(prefix + "not an image OpenCV can read");
    if (bgr.cols > 16384 || bgr.rows > 16384)
        throw std::runtime_error(prefix + "larger than 16384 pixels on a side");

    vision::ImageBuffer rgb(bgr.cols, bgr.rows, vision::PixelFormat::RGB24);
    const vision::ImageView view = rgb.view();
    // Convert straight into the buffer (its padded stride) instead of through another Mat.
    cv::Mat target(view.height, view.width, CV_8UC3, view.data,
                   static_cast<std::size_t>(view.stride));
    cv::cvtColor(bgr, target, cv::COLOR_BGR2RGB);
    return rgb;
}

}  // namespace platform
