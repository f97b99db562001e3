#pragma once
// The stand-in for the AAM fit until vision's fit lands, and a reference row after: NOT a fit.
// The tracked CANDIDE mesh's mean frontal shape placed by the face box alone: each vertex at
// box centre + box width x its mean offset, the offsets measured (in box widths) on the frontal
// neutral IMM photographs of the persons the demo model is built from, through their 5.3.1
// CANDIDE fits and the detector's boxes on them. It has no pose and no expression.

#include "dlib_peer.hpp"
#include "head_fit_runner.hpp"

namespace mirror_eval {

class MeanShapeBaseline final : public HeadFitRunner {
public:
    /// Reads CANDIDE-3 and calibrates on the IMM photographs under `dataDir`. Throws
    /// std::runtime_error (one line) when they cannot be read or the detector finds none.
    MeanShapeBaseline(const std::string& dataDir, DlibPeer& boxes);

    std::string label() const override;
    bool placeholder() const override { return true; }
    const vision::CandideMesh& mesh() const override { return mesh_; }
    void restart() override {}
    HeadFit fit(const cv::Mat& grey, const FaceBoxPx& box) override;

    int calibrationPhotos() const noexcept { return photos_; }
    /// Per vertex, its mean offset from the box centre in box widths.
    const std::vector<Eigen::Vector2d>& offsets() const noexcept { return offsets_; }

private:
    vision::CandideMesh mesh_;
    std::vector<Eigen::Vector2d> offsets_;  ///< per vertex, in box widths from the box centre
    int photos_ = 0;
};

}  // namespace mirror_eval
