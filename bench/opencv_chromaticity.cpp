#include "opencv_chromaticity.hpp"

#include <opencv2/core.hpp>

namespace bench {

void Table1Chromaticity::run(const cv::Mat& bgr)
{
    // split into R, G, and B
    // (cvSplit(m_inputImage, m_planes[2], m_planes[1], m_planes[0], 0): the frame is B, G, R.)
    cv::Mat split[3] = {m_planes[2], m_planes[1], m_planes[0]};
    cv::split(bgr, split);
    if (m_planes[0].empty()) {  // first call: adopt the planes split() allocated
        m_planes[2] = split[0];
        m_planes[1] = split[1];
        m_planes[0] = split[2];
    }
    // divide by 3 so sum will still fit in 8 bits
    m_planes[0].convertTo(m_planes[0], -1,
                          0.3333);  // cvConvertScale(m_planes[0], m_planes[0], 0.3333)
    m_planes[1].convertTo(m_planes[1], -1, 0.3333);
    m_planes[2].convertTo(m_planes[2], -1, 0.3333);
    // find R+G+B
    cv::add(m_planes[0], m_planes[1], sumImage);
    cv::add(m_planes[2], sumImage, sumImage);
    // divide each plane by sum
    cv::divide(m_planes[0], sumImage, m_planes[0], 255.0);
    cv::divide(m_planes[1], sumImage, m_planes[1], 255.0);
    cv::divide(m_planes[2], sumImage, m_planes[2], 255.0);
}

namespace {

// convertTo(CV_8U) rounds halves to even; ours rounds them up. 255 c / sum is either an exact half
// or at least 1/1530 away from one, so scaling by (1 + 2^-20) (at most 0.00025 at 255) lifts exact
// halves over the tie without moving any other result across a rounding boundary.
constexpr double kScale = 255.0 * (1.0 + 1.0 / (1 << 20));

}  // namespace

void FloatChromaticity::run(const cv::Mat& bgr)
{
    cv::split(bgr, bgr8_);
    for (int c = 0; c < 3; ++c)
        bgr8_[c].convertTo(bgrF_[c], CV_32F);
    cv::add(bgrF_[0], bgrF_[1], sum_);
    cv::add(sum_, bgrF_[2], sum_);
    if (variant_ == Variant::Divide) {
        for (int c = 0; c < 3; ++c) {
            // 0 / 0 is NaN in float, and NaN converts to 0: black stays 0 as specified.
            cv::divide(bgrF_[c], sum_, quotient_, kScale);
            quotient_.convertTo(out_[c], CV_8U);
        }
    } else {
        cv::divide(kScale, sum_, inverse_);
        for (int c = 0; c < 3; ++c) {
            cv::multiply(bgrF_[c], inverse_, quotient_);
            quotient_.convertTo(out_[c], CV_8U);
        }
    }
}

}  // namespace bench
