#pragma once
// The peers from OpenCV: the dissertation's Table 1 (fast, inexact) and the exact float
// formulation a careful OpenCV user writes today. Buffers are kept between calls, so a call after
// the first allocates nothing.

#include <opencv2/core.hpp>

namespace bench {

/// The dissertation's Table 1 (4.3), its OpenCV 1.x C calls in today's C++ API, step for step:
/// split, scale each plane by 0.3333 in 8 bits (so the sum fits in 8 bits), add, divide by the sum
/// with scale 255. Dividing first in 8 bits collapses dark pixels (1,1,1 -> 0,0,0 -> 0): the error
/// is up to 255.
class Table1Chromaticity {
public:
    /// `bgr`: 8-bit BGR. Results in r(), g(), b().
    void run(const cv::Mat& bgr);
    const cv::Mat& r() const { return m_planes[0]; }
    const cv::Mat& g() const { return m_planes[1]; }
    const cv::Mat& b() const { return m_planes[2]; }

private:
    cv::Mat m_planes[3];
    cv::Mat sumImage;
};

/// Exact chromaticity with OpenCV in float: convert each plane to float, sum, divide, convert
/// back to 8 bits. Variant Divide divides each plane by the sum (the textbook form); Reciprocal
/// computes 255/sum once and multiplies (one divide instead of three). Both round like ours.
class FloatChromaticity {
public:
    enum class Variant { Divide, Reciprocal };
    explicit FloatChromaticity(Variant variant) : variant_(variant) {}

    void run(const cv::Mat& bgr);
    const cv::Mat& r() const { return out_[2]; }
    const cv::Mat& g() const { return out_[1]; }
    const cv::Mat& b() const { return out_[0]; }

private:
    Variant variant_;
    cv::Mat bgr8_[3];
    cv::Mat bgrF_[3];
    cv::Mat sum_;
    cv::Mat inverse_;
    cv::Mat quotient_;
    cv::Mat out_[3];  ///< b, g, r
};

}  // namespace bench
