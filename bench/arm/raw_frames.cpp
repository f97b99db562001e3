// raw-frames: decodes image files (PNG, JPEG: whatever OpenCV reads) on the host into one file of
// raw BGR24 frames back to back, WxH each, for vision-frame-loop, which runs under qemu-aarch64
// without OpenCV. A larger image gives its middle WxH (FGNet's 720x576 frames: the 720x480 a
// 720x480 camera would see); a smaller one is an error.
//
//   raw-frames --size 720x480 --out F.raw IMAGE...
#include <cstdio>
#include <exception>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>

int main(int argc, char** argv)
{
    try {
        int w = 0, h = 0, first = 5;
        if (argc < 6 || std::string(argv[1]) != "--size" ||
            std::sscanf(argv[2], "%dx%d", &w, &h) != 2 || std::string(argv[3]) != "--out")
            throw std::runtime_error("usage: raw-frames --size WxH --out F.raw IMAGE...");
        std::ofstream out(argv[4], std::ios::binary);
        if (!out)
            throw std::runtime_error(std::string("cannot write ") + argv[4]);
        for (int i = first; i < argc; ++i) {
            const cv::Mat m = cv::imread(argv[i], cv::IMREAD_COLOR);
            if (m.empty() || m.cols < w || m.rows < h)
                throw std::runtime_error(std::string(argv[i]) + ": unreadable or smaller than " +
                                         argv[2]);
            const cv::Mat crop = m(cv::Rect((m.cols - w) / 2, (m.rows - h) / 2, w, h));
            for (int y = 0; y < h; ++y)
                out.write(reinterpret_cast<const char*>(crop.ptr(y)), 3L * w);
        }
        if (!out.flush())
            throw std::runtime_error(std::string("cannot write ") + argv[4]);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raw-frames: %s\n", e.what());
        return 1;
    }
}
