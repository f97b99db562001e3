#pragma once
// The chromaticity contenders on one frame, each a call that converts the whole frame: the memory
// floor (memcpy), the dissertation's Table 1 (OpenCV) and Table 5 (look-up loop), OpenCV's exact
// float formulation, and ours. Google Benchmark and the --ratios mode both time these calls.

#include "opencv_chromaticity.hpp"
#include "seed_table5.hpp"
#include "vision/chromaticity.hpp"

#include <opencv2/core.hpp>
#include <vector>

namespace bench {

class ChromaticityCases {
public:
    /// `bgr`: the 8-bit BGR frame (kept by reference, must outlive this).
    explicit ChromaticityCases(const cv::Mat& bgr);

    void memcpyFrame();
    void table1OpenCv() { table1_.run(frame_); }
    void floatDivideOpenCv() { floatDivide_.run(frame_); }
    void floatReciprocalOpenCv() { floatReciprocal_.run(frame_); }
    void seedTable5();
    /// Ours as the pipeline calls it (the overload without a path: the best one).
    void ours();
    /// Ours on one concrete path (Scalar, Sse2, ...); see concretePaths().
    void oursOn(vision::ChromaticityPath path);
    /// The concrete paths this build and CPU can run.
    static std::vector<vision::ChromaticityPath> concretePaths();

    /// Runs every contender (and each of our paths) once and prints its largest error against
    /// round(255 c / sum) on the frame. Returns false when ours (any path) or OpenCV's exact
    /// formulation is not exact.
    bool checkExactness();

    const cv::Mat& frame() const { return frame_; }
    const vision::ChromaticityTable& table() const { return table_; }
    vision::ChromaticityPlanes oursPlanes();

private:
    void poisonOurs();

    const cv::Mat& frame_;
    cv::Mat copy_;
    Table1Chromaticity table1_;
    FloatChromaticity floatDivide_{FloatChromaticity::Variant::Divide};
    FloatChromaticity floatReciprocal_{FloatChromaticity::Variant::Reciprocal};
    cv::Mat seedPlanes_[3];
    vision::ChromaticityTable table_;
    cv::Mat r_, g_, b_;
};

}  // namespace bench
