#pragma once
// The face benchmarks (§3), ours beside the peer (OpenCV, one thread), on real frames of the
// FGNet talking face (../shared/data/fgnet_talking_face/images, 720x576 JPEG):
//  - Viola-Jones full-frame detection at 360x240 (frame 0, its middle 720x480 shrunk by 2), our
//    FaceDetector against cv::CascadeClassifier::detectMultiScale with the same cascade,
//    scaleFactor 1.1, minNeighbors 3, minSize 24x24 (config/mirror.toml's [faces] defaults);
//  - mixture of Gaussians at 360x240 over the first kMotionFrames frames (grey, shrunk by 2),
//    our MotionDetector (K=3) against cv::BackgroundSubtractorMOG2 with 3 mixtures, no shadows,
//    the same learning rate, thresholds and variances;
//  - pyramidal Lucas-Kanade: 50 corners of the face, 3 levels (maxLevel 2), window 15, from frame
//    0 to frame 1, each call building the new frame's pyramid: our ImagePyramid +
//    PyramidalLucasKanade (no forward-backward check, as one OpenCV call) against
//    cv::buildOpticalFlowPyramid + cv::calcOpticalFlowPyrLK; at 360x240 (the working resolution
//    the tracker runs at) and at the frames' own 720x576 (as tests/peer/optical_flow_peer_test);
//  - the whole face pipeline per camera frame: MotionStage (downscale 2) + FaceStage + AamStage
//    (when the demo AAM model out/aam/imm-demo.aam is built: scripts/dev model) on the 720x576
//    frames in order, as the firmware's defaults configure them; the AAM fit timed on its own,
//    beside dlib's 68-point shape predictor given the same faces' boxes (AamPeerTiming).

#include "vision/aam_model.hpp"
#include "vision/aam_stage.hpp"
#include "vision/face_detector.hpp"
#include "vision/face_stage.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"
#include "vision/image_pyramid.hpp"
#include "vision/motion_detector.hpp"
#include "vision/motion_stage.hpp"
#include "vision/optical_flow.hpp"

#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/objdetect.hpp>
#include <opencv2/video/background_segm.hpp>
#include <string>
#include <vector>

namespace bench {

class FaceCases {
public:
    static constexpr int kMotionFrames = 60;
    static constexpr int kFlowPoints = 50;

    /// Finds the FGNet frames and the cascades, decodes the frames the timed cases use and builds
    /// every contender. Throws std::runtime_error (one line naming the path) when data is
    /// missing.
    FaceCases();
    ~FaceCases();

    /// Cascades compared: 0 = haarcascade_frontalface_default.xml (the configured one), 1 = alt2.
    int cascadeCount() const { return static_cast<int>(cascades_.size()); }
    const std::string& cascadeName(int i) const;
    /// One full-frame detection of the 360x240 frame; returns the faces found.
    int detectOurs(int cascade);
    int detectOpenCv(int cascade);

    /// One frame of background subtraction (the frames cycle).
    void motionOurs();
    void motionOpenCv();

    /// The new frame's pyramid and 50 points tracked into it; returns the points tracked.
    /// Resolution 0: 360x240 (working), 1: 720x576 (the frames' own).
    static constexpr int kFlowResolutions = 2;
    static const char* flowResolutionName(int resolution);
    int flowOurs(int resolution);
    int flowOpenCv(int resolution);

    /// The face pipeline on the FGNet frames in order. restart() builds fresh stages;
    /// load(i) decodes frame i (not to be timed); step() runs the motion and face stages on it,
    /// stepAam() then the AAM stage (nothing without a model).
    int pipelineFrames() const { return static_cast<int>(framePaths_.size()); }
    void pipelineRestart();
    void pipelineLoad(int i);
    void pipelineStep();
    void pipelineStepAam();
    /// Faces shown (confirmed) after the last step().
    int pipelineShownFaces() const;

    /// The AAM model's path and whether it loaded (the AAM lines need it).
    const std::string& aamModelPath() const { return aamModelPath_; }
    bool hasAam() const { return aamModel_ != nullptr; }
    /// The last stepAam()'s fits: faces fitted and their Gauss-Newton iterations.
    int pipelineFitsRun() const;
    int pipelineFitIterations() const;
    /// The last step()'s shown faces' boxes in frame pixels, the boxes the AAM fit starts from.
    std::vector<cv::Rect> pipelineShownBoxes() const;
    /// The last loaded frame (BGR 720x576).
    const cv::Mat& pipelineFrame() const { return pipelineFrame_; }

    const std::string& imageDir() const { return imageDir_; }

private:
    struct Cascade;

    std::string imageDir_;
    std::vector<std::string> framePaths_;

    cv::Mat detectFrame_;  // 360x240 grey
    std::vector<std::unique_ptr<Cascade>> cascades_;

    std::vector<vision::ImageBuffer> motionFrames_;  // 360x240 grey
    std::unique_ptr<vision::MotionDetector> motion_;
    vision::ImageBuffer motionMask_;
    cv::Ptr<cv::BackgroundSubtractorMOG2> mog2_;
    cv::Mat mog2Mask_;
    int motionNext_ = 0;
    int mog2Next_ = 0;

    struct Flow;
    std::vector<std::unique_ptr<Flow>> flows_;  // per resolution

    vision::HaarCascade pipelineCascade_;
    cv::Mat pipelineFrame_;  // BGR 720x576
    std::unique_ptr<vision::MotionStage> motionStage_;
    std::unique_ptr<vision::FaceStage> faceStage_;
    std::string aamModelPath_;
    std::unique_ptr<vision::AamModel> aamModel_;
    std::unique_ptr<vision::AamStage> aamStage_;
    vision::FrameState pipelineState_;
    std::uint64_t pipelineSequence_ = 0;
};

}  // namespace bench
