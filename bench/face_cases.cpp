#include "face_cases.hpp"

#include "vision/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>
#include <string>

namespace bench {

namespace {

constexpr double kScaleFactor = 1.1;  // config/mirror.toml [faces] scale_factor
constexpr int kMinNeighbors = 3;      // min_neighbors
constexpr int kMinSize = 24;          // min_size (working resolution)
constexpr int kWorkWidth = 360;
constexpr int kWorkHeight = 240;
constexpr int kFlowWindow = 15;
constexpr int kFlowMaxLevel = 2;  // 3 levels
// The middle 720x480 of a 720x576 FGNet frame, as a 720x480 camera would see it.
constexpr int kCropTop = 48;

const char* const kCascadeFiles[] = {
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml",
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_alt2.xml",
};

std::string sharedData(const std::string& relative)
{
    return (std::filesystem::path(MIRROR_SOURCE_DIR) / ".." / "shared" / "data" / relative)
        .lexically_normal()
        .string();
}

cv::Mat readColor(const std::string& path)
{
    cv::Mat m = cv::imread(path, cv::IMREAD_COLOR);
    if (m.empty())
        throw std::runtime_error("mirror-bench: cannot read the frame " + path);
    return m;
}

vision::ConstImageView viewOf(const cv::Mat& m, vision::PixelFormat format)
{
    return {m.data, m.cols, m.rows, static_cast<int>(m.step[0]), format};
}

cv::Mat matOf(const vision::ConstImageView& v)
{
    return cv::Mat(v.height, v.width, CV_8UC1, const_cast<std::uint8_t*>(v.data),
                   static_cast<std::size_t>(v.stride));
}

// The FGNet frame's middle 720x480 in grey at 360x240, as the motion stage makes it.
vision::ImageBuffer workingGray(const cv::Mat& bgr)
{
    const cv::Mat crop = bgr(cv::Rect(0, kCropTop, 2 * kWorkWidth, 2 * kWorkHeight));
    vision::ImageBuffer out(kWorkWidth, kWorkHeight, vision::PixelFormat::Gray8);
    if (!vision::downscaleToGray(viewOf(crop, vision::PixelFormat::BGR24), 2, out.view()))
        throw std::runtime_error("mirror-bench: cannot shrink an FGNet frame to 360x240");
    return out;
}

// The whole 720x576 frame in grey (the LK peer test's resolution).
vision::ImageBuffer fullGray(const cv::Mat& bgr)
{
    vision::ImageBuffer out(bgr.cols, bgr.rows, vision::PixelFormat::Gray8);
    if (!vision::downscaleToGray(viewOf(bgr, vision::PixelFormat::BGR24), 1, out.view()))
        throw std::runtime_error("mirror-bench: cannot convert an FGNet frame to grey");
    return out;
}

// The bounding box of a frame's 68 annotated landmarks.
cv::Rect2f landmarkBox(const std::string& ptsPath)
{
    std::ifstream in(ptsPath);
    if (!in)
        throw std::runtime_error("mirror-bench: cannot read the landmarks " + ptsPath);
    std::string line;
    float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
    while (std::getline(in, line)) {
        float x = 0.f, y = 0.f;
        if (std::sscanf(line.c_str(), "%f %f", &x, &y) == 2) {
            x0 = std::min(x0, x);
            y0 = std::min(y0, y);
            x1 = std::max(x1, x);
            y1 = std::max(y1, y);
        }
    }
    if (x1 < x0)
        throw std::runtime_error("mirror-bench: no landmarks in " + ptsPath);
    return {x0, y0, x1 - x0, y1 - y0};
}

vision::MotionDetectorOptions motionOptions()
{
    vision::MotionDetectorOptions o;  // K=3, a=0.005, T=0.7, 2.5 sigma: the firmware's defaults
    o.components = 3;
    return o;
}

}  // namespace

// One LK pair: frames 0 and 1 in grey, the corners, both trackers and their buffers.
struct FaceCases::Flow {
    vision::ImageBuffer a, b;
    vision::ImagePyramid prev, next;
    std::unique_ptr<vision::PyramidalLucasKanade> lk;
    std::vector<vision::Point2f> from, to;
    std::vector<vision::FlowStatus> status;
    std::vector<cv::Mat> cvPrev, cvNext;
    std::vector<cv::Point2f> cvFrom, cvTo;
    std::vector<std::uint8_t> cvStatus;
    std::vector<float> cvError;

    // 50 Shi-Tomasi corners of `box` in a (as the tracker finds them), the previous pyramids.
    void setUp(const cv::Rect& box)
    {
        const cv::Mat m = matOf(a.view());
        cv::Mat mask = cv::Mat::zeros(m.size(), CV_8U);
        mask(box & cv::Rect(0, 0, m.cols, m.rows)).setTo(255);
        for (const double minDistance : {3.0, 2.0, 1.0}) {
            cv::goodFeaturesToTrack(m, cvFrom, kFlowPoints, 0.01, minDistance, mask, 3, false);
            if (cvFrom.size() >= static_cast<std::size_t>(kFlowPoints))
                break;
        }
        if (cvFrom.size() < static_cast<std::size_t>(kFlowPoints))
            throw std::runtime_error("mirror-bench: fewer than 50 corners in the FGNet face");
        for (const cv::Point2f& p : cvFrom)
            from.push_back({p.x, p.y});
        to.resize(from.size());
        status.resize(from.size());
        const vision::Size size{m.cols, m.rows};
        prev = vision::ImagePyramid(size, kFlowMaxLevel + 1);
        next = vision::ImagePyramid(size, kFlowMaxLevel + 1);
        prev.build(a.view());
        vision::OpticalFlowOptions o;
        o.window = kFlowWindow;
        o.maxLevel = kFlowMaxLevel;
        o.maxIterations = 30;
        o.epsilon = 0.01f;
        o.fbThreshold = 0.f;  // one OpenCV call has no backward pass either
        lk = std::make_unique<vision::PyramidalLucasKanade>(o);
        cv::buildOpticalFlowPyramid(m, cvPrev, cv::Size(kFlowWindow, kFlowWindow), kFlowMaxLevel);
    }
};

struct FaceCases::Cascade {
    std::string name;
    std::unique_ptr<vision::FaceDetector> ours;
    cv::CascadeClassifier theirs;
    std::vector<cv::Rect> theirFaces;
};

FaceCases::FaceCases() : imageDir_(sharedData("fgnet_talking_face/images"))
{
    if (!std::filesystem::is_directory(imageDir_))
        throw std::runtime_error("mirror-bench: no FGNet frames in " + imageDir_);
    for (const auto& e : std::filesystem::directory_iterator(imageDir_)) {
        if (e.path().extension() == ".jpg")
            framePaths_.push_back(e.path().string());
    }
    std::sort(framePaths_.begin(), framePaths_.end());
    if (framePaths_.size() < static_cast<std::size_t>(kMotionFrames))
        throw std::runtime_error("mirror-bench: too few FGNet frames in " + imageDir_);

    // Detection: frame 0 at the working resolution.
    const cv::Mat first = readColor(framePaths_[0]);
    const vision::ImageBuffer firstGray = workingGray(first);
    detectFrame_ = matOf(firstGray.view()).clone();
    for (const char* file : kCascadeFiles) {
        auto c = std::make_unique<Cascade>();
        c->name = std::filesystem::path(file).filename().string();
        if (!c->theirs.load(file))
            throw std::runtime_error(std::string("mirror-bench: OpenCV cannot load ") + file);
        vision::FaceDetectorOptions o;
        o.maxFrameSize = {kWorkWidth, kWorkHeight};
        o.scaleFactor = kScaleFactor;
        o.minNeighbors = kMinNeighbors;
        o.minSize = {kMinSize, kMinSize};
        c->ours = std::make_unique<vision::FaceDetector>(vision::loadHaarCascade(file), o);
        cascades_.push_back(std::move(c));
    }

    // Motion: the first frames, grey 360x240.
    for (int i = 0; i < kMotionFrames; ++i)
        motionFrames_.push_back(workingGray(readColor(framePaths_[static_cast<std::size_t>(i)])));
    const vision::MotionDetectorOptions mo = motionOptions();
    motion_ = std::make_unique<vision::MotionDetector>(vision::Size{kWorkWidth, kWorkHeight}, mo);
    motionMask_ = vision::ImageBuffer(kWorkWidth, kWorkHeight, vision::PixelFormat::Gray8);
    // MOG2 as close to our model as its parameters allow (tests/peer/motion_peer_test.cpp):
    // same K, T, match threshold, variances; no shadows, no complexity-reduction prior.
    const double lambda2 = static_cast<double>(mo.matchThreshold) * mo.matchThreshold;
    mog2_ = cv::createBackgroundSubtractorMOG2(static_cast<int>(1.0f / mo.learningRate), lambda2,
                                               false);
    mog2_->setNMixtures(mo.components);
    mog2_->setBackgroundRatio(mo.backgroundRatio);
    mog2_->setVarThresholdGen(lambda2);
    mog2_->setVarInit(mo.initialVariance);
    mog2_->setVarMin(mo.minVariance);
    mog2_->setVarMax(mo.maxVariance);
    mog2_->setComplexityReductionThreshold(0.0);

    // Flow: 50 corners of the face in frame 0, tracked into frame 1.
    const std::string pts0 =
        (std::filesystem::path(imageDir_).parent_path() / "points" / "franck_00000.pts").string();
    const cv::Rect2f face = landmarkBox(pts0);
    const cv::Mat second = readColor(framePaths_[1]);
    auto working = std::make_unique<Flow>();
    working->a = workingGray(first);
    working->b = workingGray(second);
    working->setUp(cv::Rect(static_cast<int>(face.x / 2), static_cast<int>((face.y - kCropTop) / 2),
                            static_cast<int>(face.width / 2), static_cast<int>(face.height / 2)));
    flows_.push_back(std::move(working));
    auto full = std::make_unique<Flow>();
    full->a = fullGray(first);
    full->b = fullGray(second);
    full->setUp(cv::Rect(static_cast<int>(face.x), static_cast<int>(face.y),
                         static_cast<int>(face.width), static_cast<int>(face.height)));
    flows_.push_back(std::move(full));

    pipelineCascade_ = vision::loadHaarCascade(kCascadeFiles[0]);
    // The demo model leaves FGNet's person out (it is built from IMM): the fit is on a face it
    // never saw, as in a home.
    aamModelPath_ = (std::filesystem::path(MIRROR_SOURCE_DIR) / "out" / "aam" / "imm-demo.aam")
                        .lexically_normal()
                        .string();
    if (std::filesystem::exists(aamModelPath_)) {
        vision::AamModelFile file = vision::loadAamModel(aamModelPath_);
        if (!file.ok)
            throw std::runtime_error("mirror-bench: " + file.problem);
        aamModel_ = std::make_unique<vision::AamModel>(std::move(file.model));
    }
    pipelineRestart();
}

FaceCases::~FaceCases() = default;

const std::string& FaceCases::cascadeName(int i) const
{
    return cascades_[static_cast<std::size_t>(i)]->name;
}

int FaceCases::detectOurs(int cascade)
{
    Cascade& c = *cascades_[static_cast<std::size_t>(cascade)];
    return c.ours->detect(viewOf(detectFrame_, vision::PixelFormat::Gray8));
}

int FaceCases::detectOpenCv(int cascade)
{
    Cascade& c = *cascades_[static_cast<std::size_t>(cascade)];
    c.theirs.detectMultiScale(detectFrame_, c.theirFaces, kScaleFactor, kMinNeighbors, 0,
                              cv::Size(kMinSize, kMinSize));
    return static_cast<int>(c.theirFaces.size());
}

void FaceCases::motionOurs()
{
    const vision::ImageBuffer& f = motionFrames_[static_cast<std::size_t>(motionNext_)];
    motion_->apply(f.view(), motionMask_.view());
    motionNext_ = (motionNext_ + 1) % kMotionFrames;
}

void FaceCases::motionOpenCv()
{
    const vision::ImageBuffer& f = motionFrames_[static_cast<std::size_t>(mog2Next_)];
    mog2_->apply(matOf(f.view()), mog2Mask_, static_cast<double>(motionOptions().learningRate));
    mog2Next_ = (mog2Next_ + 1) % kMotionFrames;
}

const char* FaceCases::flowResolutionName(int resolution)
{
    return resolution == 0 ? "360x240" : "720x576";
}

int FaceCases::flowOurs(int resolution)
{
    Flow& f = *flows_[static_cast<std::size_t>(resolution)];
    f.next.build(f.b.view());
    return f.lk->track(f.prev, f.next, f.from.data(), f.to.data(), f.status.data(),
                       static_cast<int>(f.from.size()));
}

int FaceCases::flowOpenCv(int resolution)
{
    Flow& f = *flows_[static_cast<std::size_t>(resolution)];
    const cv::Size win(kFlowWindow, kFlowWindow);
    cv::buildOpticalFlowPyramid(matOf(f.b.view()), f.cvNext, win, kFlowMaxLevel);
    cv::calcOpticalFlowPyrLK(
        f.cvPrev, f.cvNext, f.cvFrom, f.cvTo, f.cvStatus, f.cvError, win, kFlowMaxLevel,
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01));
    return static_cast<int>(std::count(f.cvStatus.begin(), f.cvStatus.end(), 1));
}

void FaceCases::pipelineRestart()
{
    aamStage_.reset();
    faceStage_.reset();
    vision::MotionStageOptions mo;
    mo.downscale = 2;
    mo.detector = motionOptions();
    motionStage_ = std::make_unique<vision::MotionStage>(vision::Size{720, 576}, mo);
    // config/mirror.toml's [faces] defaults.
    vision::FaceTrackerOptions o;
    o.detector.scaleFactor = kScaleFactor;
    o.detector.minNeighbors = kMinNeighbors;
    o.detector.minSize = {kMinSize, kMinSize};
    o.mode = vision::FaceTrackingMode::Similarity;
    o.useMotionMask = true;
    o.confirmFrames = 2;
    o.graceFrames = 5;
    o.maxFaces = 8;
    o.detectionWindowBudget = 0;
    faceStage_ = std::make_unique<vision::FaceStage>(*motionStage_, pipelineCascade_, o);
    if (aamModel_)
        aamStage_ = std::make_unique<vision::AamStage>(*motionStage_, *faceStage_, *aamModel_);
    pipelineSequence_ = 0;
}

void FaceCases::pipelineLoad(int i)
{
    pipelineFrame_ = readColor(framePaths_[static_cast<std::size_t>(i)]);
    if (pipelineFrame_.cols != 720 || pipelineFrame_.rows != 576)
        throw std::runtime_error("mirror-bench: FGNet frame is not 720x576: " +
                                 framePaths_[static_cast<std::size_t>(i)]);
}

void FaceCases::pipelineStep()
{
    vision::FrameState& state = pipelineState_;
    state = {};
    state.frame.image = viewOf(pipelineFrame_, vision::PixelFormat::BGR24);
    state.frame.sequence = pipelineSequence_;
    state.frame.timestampNs = static_cast<std::int64_t>(pipelineSequence_) * 40'000'000;  // 25 Hz
    ++pipelineSequence_;
    motionStage_->process(state);
    faceStage_->process(state);
}

void FaceCases::pipelineStepAam()
{
    if (aamStage_)
        aamStage_->process(pipelineState_);
}

int FaceCases::pipelineFitsRun() const
{
    int n = 0;
    for (const vision::FaceFit& f : pipelineState_.fits)
        n += f.fitted;
    return n;
}

int FaceCases::pipelineFitIterations() const
{
    int n = 0;
    for (const vision::FaceFit& f : pipelineState_.fits)
        n += f.fitted ? f.iterations : 0;
    return n;
}

std::vector<cv::Rect> FaceCases::pipelineShownBoxes() const
{
    std::vector<cv::Rect> boxes;
    for (const vision::TrackedFace& f : faceStage_->faces()) {
        if (!f.shown())
            continue;
        // FaceStage::faces() is in frame coordinates already.
        boxes.emplace_back(static_cast<int>(std::lround(f.centre.x - f.size / 2)),
                           static_cast<int>(std::lround(f.centre.y - f.size / 2)),
                           static_cast<int>(std::lround(f.size)),
                           static_cast<int>(std::lround(f.size)));
    }
    return boxes;
}

int FaceCases::pipelineShownFaces() const
{
    int shown = 0;
    for (const vision::TrackedFace& f : faceStage_->faces())
        shown += f.shown();
    return shown;
}

}  // namespace bench
