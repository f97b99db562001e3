#pragma once
// The runner around vision's AAM fit (§5.3) as the firmware runs it: vision::TrackedFaceFitter,
// one track followed from frame to frame while its fit holds and started afresh from the box
// otherwise. The box `mirror-eval aam` gives both peers is dlib's HOG box, not the tracker's
// Viola-Jones box the firmware's AamBoxPlacement was measured on, so the placement is measured
// again here on dlib's boxes: the mesh box of the mean shape baseline's calibration (the same IMM
// photographs, their 5.3.1 CANDIDE fits against the boxes).

#include "dlib_peer.hpp"
#include "head_fit_runner.hpp"
#include "vision/aam_model.hpp"
#include "vision/tracked_face_fitter.hpp"

#include <memory>

namespace mirror_eval {

class AamFitRunner final : public HeadFitRunner {
public:
    /// Loads `modelPath` and calibrates the placement on dlib's boxes (MeanShapeBaseline's
    /// calibration under `dataDir`). Throws std::runtime_error (one line) when either fails.
    AamFitRunner(const std::string& modelPath, const std::string& dataDir, DlibPeer& boxes);

    std::string label() const override;
    bool placeholder() const override { return false; }
    const vision::CandideMesh& mesh() const override { return model_.mesh; }
    void restart() override { fitter_->reset(); }
    HeadFit fit(const cv::Mat& grey, const FaceBoxPx& box) override;

    const vision::AamBoxPlacement& placement() const noexcept { return placement_; }

private:
    vision::AamModel model_;
    vision::AamBoxPlacement placement_;
    std::unique_ptr<vision::TrackedFaceFitter> fitter_;
};

}  // namespace mirror_eval
