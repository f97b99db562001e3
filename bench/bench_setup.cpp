#include "bench_setup.hpp"

#include <sched.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace bench {

int pinToLowestCpu()
{
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0)
        return -1;
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
        if (!CPU_ISSET(cpu, &allowed))
            continue;
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(cpu, &one);
        return sched_setaffinity(0, sizeof(one), &one) == 0 ? cpu : -1;
    }
    return -1;
}

std::string findPhoto(const std::string& requested)
{
    if (!requested.empty())
        return requested;
    // The shared real data beside the project first; on a board without it, a photograph from
    // Debian's opencv-doc (in the project's package list).
    const std::string candidates[] = {
        (std::filesystem::path(MIRROR_SOURCE_DIR) / ".." / "shared" / "data" /
         "debian_skimage_faces" / "astronaut.png")
            .lexically_normal()
            .string(),
        "/usr/share/doc/opencv-doc/examples/data/fruits.jpg",
    };
    for (const auto& c : candidates)
        if (std::filesystem::exists(c))
            return c;
    return {};
}

cv::Mat loadFrame(const std::string& path)
{
    const cv::Mat photo = cv::imread(path, cv::IMREAD_COLOR);
    if (photo.empty())
        throw std::runtime_error("mirror-bench: cannot read the photograph " + path +
                                 " (missing or not an image OpenCV can decode)");
    cv::Mat frame;
    cv::resize(photo, frame, cv::Size(kFrameWidth, kFrameHeight), 0, 0, cv::INTER_AREA);
    return frame.isContinuous() ? frame : frame.clone();
}

vision::ConstImageView bgrView(const cv::Mat& bgr)
{
    return {bgr.data, bgr.cols, bgr.rows, static_cast<int>(bgr.step[0]),
            vision::PixelFormat::BGR24};
}

int maxChromaticityError(const cv::Mat& bgr, const cv::Mat& r, const cv::Mat& g, const cv::Mat& b)
{
    int worst = 0;
    for (int y = 0; y < bgr.rows; ++y) {
        const std::uint8_t* in = bgr.ptr<std::uint8_t>(y);
        const std::uint8_t* out[3] = {b.ptr<std::uint8_t>(y), g.ptr<std::uint8_t>(y),
                                      r.ptr<std::uint8_t>(y)};
        for (int x = 0; x < bgr.cols; ++x) {
            const int sum = in[3 * x] + in[3 * x + 1] + in[3 * x + 2];
            for (int c = 0; c < 3; ++c)
                worst =
                    std::max(worst, std::abs(out[c][x] - exactChromaticity(in[3 * x + c], sum)));
        }
    }
    return worst;
}

}  // namespace bench
