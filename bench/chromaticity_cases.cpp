#include "chromaticity_cases.hpp"

#include "bench_setup.hpp"

#include <cstdio>
#include <cstring>

namespace bench {

namespace {

vision::ImageView grayView(cv::Mat& m)
{
    return {m.data, m.cols, m.rows, static_cast<int>(m.step[0]), vision::PixelFormat::Gray8};
}

}  // namespace

ChromaticityCases::ChromaticityCases(const cv::Mat& bgr) : frame_(bgr)
{
    copy_.create(bgr.size(), bgr.type());
    for (auto& p : seedPlanes_)
        p.create(bgr.size(), CV_8UC1);
    r_.create(bgr.size(), CV_8UC1);
    g_.create(bgr.size(), CV_8UC1);
    b_.create(bgr.size(), CV_8UC1);
    seedInitChromaticityTable();
    // First runs allocate the OpenCV formulations' buffers, so timed runs do not.
    table1OpenCv();
    floatDivideOpenCv();
    floatReciprocalOpenCv();
}

void ChromaticityCases::memcpyFrame()
{
    std::memcpy(copy_.data, frame_.data, frame_.total() * frame_.elemSize());
}

void ChromaticityCases::seedTable5()
{
    SeedIplImage input{reinterpret_cast<char*>(frame_.data)};
    SeedIplImage planes[3] = {{reinterpret_cast<char*>(seedPlanes_[0].data)},
                              {reinterpret_cast<char*>(seedPlanes_[1].data)},
                              {reinterpret_cast<char*>(seedPlanes_[2].data)}};
    SeedIplImage* const planePtrs[3] = {&planes[0], &planes[1], &planes[2]};
    seedChromaticityTable5(&input, planePtrs, {frame_.cols, frame_.rows});
}

vision::ChromaticityPlanes ChromaticityCases::oursPlanes()
{
    return {grayView(r_), grayView(g_), grayView(b_)};
}

void ChromaticityCases::ours()
{
    vision::convertChromaticity(table_, bgrView(frame_), oursPlanes());
}

void ChromaticityCases::oursOn(vision::ChromaticityPath path)
{
    vision::convertChromaticity(table_, bgrView(frame_), oursPlanes(), path);
}

std::vector<vision::ChromaticityPath> ChromaticityCases::concretePaths()
{
    std::vector<vision::ChromaticityPath> paths;
    // Every enumerator before Best is a concrete path (the enum grows as paths are added).
    const int best = static_cast<int>(vision::ChromaticityPath::Best);
    for (int i = 0; i < best; ++i) {
        const auto path = static_cast<vision::ChromaticityPath>(i);
        if (vision::chromaticityPathAvailable(path))
            paths.push_back(path);
    }
    return paths;
}

void ChromaticityCases::poisonOurs()
{
    // A call that writes nothing (a refused path) must not pass on the previous call's output.
    for (cv::Mat* plane : {&r_, &g_, &b_})
        plane->setTo(cv::Scalar(77));
}

bool ChromaticityCases::checkExactness()
{
    std::printf("exactness (max |out - round(255 c / sum)| on the %dx%d frame):\n", frame_.cols,
                frame_.rows);
    bool pathsExact = true;
    for (auto path : concretePaths()) {
        poisonOurs();
        const bool ok = vision::convertChromaticity(table_, bgrView(frame_), oursPlanes(), path);
        const int err = ok ? maxChromaticityError(frame_, r_, g_, b_) : 255;
        pathsExact = pathsExact && err == 0;
        std::printf("  ours_%-21s %3d\n", vision::chromaticityPathName(path), err);
    }
    poisonOurs();
    ours();  // exactly the call that is timed
    table1OpenCv();
    floatDivideOpenCv();
    floatReciprocalOpenCv();
    seedTable5();
    const int oursErr = maxChromaticityError(frame_, r_, g_, b_);
    const int table1Err = maxChromaticityError(frame_, table1_.r(), table1_.g(), table1_.b());
    const int divideErr =
        maxChromaticityError(frame_, floatDivide_.r(), floatDivide_.g(), floatDivide_.b());
    const int reciprocalErr = maxChromaticityError(frame_, floatReciprocal_.r(),
                                                   floatReciprocal_.g(), floatReciprocal_.b());
    // The seed planes follow the frame's byte order: B, G, R.
    const int seedErr =
        maxChromaticityError(frame_, seedPlanes_[2], seedPlanes_[1], seedPlanes_[0]);
    char best[64];
    std::snprintf(best, sizeof best, "ours (best = %s)",
                  vision::chromaticityPathName(vision::bestChromaticityPath()));
    std::printf("  %-26s %3d\n", best, oursErr);
    std::printf("  %-26s %3d\n", "opencv_float_divide", divideErr);
    std::printf("  %-26s %3d\n", "opencv_float_reciprocal", reciprocalErr);
    std::printf("  %-26s %3d   (cvRound: ties to even)\n", "seed_table5_lut", seedErr);
    std::printf("  %-26s %3d   (8-bit divide by 3 first)\n", "opencv_table1", table1Err);
    return pathsExact && oursErr == 0 && divideErr == 0 && reciprocalErr == 0;
}

}  // namespace bench
