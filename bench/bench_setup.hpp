#pragma once
// What every benchmark of mirror-bench shares: the process pinned to one core, the 720x480 test
// frame made from a real photograph, and the exact chromaticity reference.

#include "vision/image.hpp"

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

namespace bench {

constexpr int kFrameWidth = 720;
constexpr int kFrameHeight = 480;

/// Pins the calling thread (and the threads it starts later) to the lowest CPU it may run on, so
/// every number is one core's. Returns the CPU, or -1 (with errno) when the kernel refused.
int pinToLowestCpu();

/// The photograph the frames are made from: `requested` if not empty, else the first of the
/// project's default real images that exists. Empty when none exists.
std::string findPhoto(const std::string& requested);

/// The benchmark frame: `path` decoded by OpenCV and resized to 720x480 BGR (8-bit, contiguous).
/// Throws std::runtime_error with one line naming the path when it cannot be read.
cv::Mat loadFrame(const std::string& path);

/// A non-owning vision view of a contiguous 8-bit BGR cv::Mat.
vision::ConstImageView bgrView(const cv::Mat& bgr);

/// The specification every exact path must meet: round(255 c / sum) with halves up, 0 for sum 0.
inline std::uint8_t exactChromaticity(int c, int sum)
{
    return sum == 0 ? 0 : static_cast<std::uint8_t>((510 * c + sum) / (2 * sum));
}

/// Largest |out - exact| over the frame for r, g, b planes (Gray8, frame size) of a BGR frame.
int maxChromaticityError(const cv::Mat& bgr, const cv::Mat& r, const cv::Mat& g, const cv::Mat& b);

}  // namespace bench
