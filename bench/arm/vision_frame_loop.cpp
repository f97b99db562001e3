// vision-frame-loop: the firmware's vision pipeline (frame check, chromaticity, card, motion,
// faces and, given a model, the AAM fit; config/mirror.toml's defaults) run over raw frames
// already in memory, with a mark before
// every stage and after the last one. Built for arm64 and run by scripts/bench-arm under
// qemu-aarch64 with bench/arm/insn_count_plugin.c, which writes the instruction count at every
// mark: per frame, the differences between consecutive marks are the stages' instruction counts.
//
//   vision-frame-loop --size 720x480 --frames F.raw --train T.raw --cascade XML [--skip N]
//                     [--model M.aam]
//
// F.raw is frames of 720x480 BGR24 bytes back to back, T.raw one frame on whose central half the
// card's colour is trained (before the loop and outside the marks, by a pipeline of its own), as
// the console's `card train` does. The first N frames of F.raw are skipped (a card sequence's
// training frame). Prints the stage names and the frame count (what the marks mean), nothing
// per frame. No OpenCV: the frames are decoded on the host (bench/arm/raw_frames.cpp).
#include "vision/aam_model.hpp"
#include "vision/aam_stage.hpp"
#include "vision/card_stage.hpp"
#include "vision/chromaticity_stage.hpp"
#include "vision/face_stage.hpp"
#include "vision/frame_check_stage.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/motion_stage.hpp"
#include "vision/pipeline.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

/// The instruction counter's mark: the plugin finds this symbol; its body must stay one `ret`.
extern "C" __attribute__((noinline, used)) void mirror_arm_mark()
{
    asm volatile("" ::: "memory");
}

namespace {

constexpr auto kFormat = vision::PixelFormat::BGR24;
constexpr float kTrainFraction = 0.5f;  // config/mirror.toml [card] train_fraction

struct Options {
    vision::Size size{720, 480};
    std::string frames, train, cascade, model;
    long skip = 0;
};

Options parse(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc)
            throw std::runtime_error("option " + a + " needs a value");
        const std::string v = argv[++i];
        if (a == "--size" && std::sscanf(v.c_str(), "%dx%d", &o.size.width, &o.size.height) == 2) {
        } else if (a == "--frames") {
            o.frames = v;
        } else if (a == "--train") {
            o.train = v;
        } else if (a == "--cascade") {
            o.cascade = v;
        } else if (a == "--model") {
            o.model = v;
        } else if (a == "--skip") {
            o.skip = std::strtol(v.c_str(), nullptr, 10);
        } else {
            throw std::runtime_error("unknown option or bad value: " + a + " " + v);
        }
    }
    if (o.frames.empty() || o.train.empty() || o.cascade.empty() || o.size.width <= 0 ||
        o.size.height <= 0)
        throw std::runtime_error(
            "usage: vision-frame-loop --size WxH --frames F.raw --train T.raw "
            "--cascade XML [--skip N] [--model M.aam]");
    return o;
}

/// Every whole frame of `path` (BGR24 of `size`, back to back).
std::vector<vision::ImageBuffer> readFrames(const std::string& path, vision::Size size)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error("cannot read " + path);
    std::vector<vision::ImageBuffer> frames;
    for (;;) {
        vision::ImageBuffer b(size.width, size.height, kFormat);
        const vision::ImageView v = b.view();
        bool whole = true;
        for (int y = 0; y < size.height && whole; ++y)
            whole = static_cast<bool>(in.read(reinterpret_cast<char*>(v.row(y)), 3L * size.width));
        if (!whole)
            break;
        frames.push_back(std::move(b));
    }
    if (frames.empty())
        throw std::runtime_error(path + " holds no whole frame of " + std::to_string(size.width) +
                                 "x" + std::to_string(size.height));
    return frames;
}

/// The card's colour model, trained on `frame` as the console's `card train` does.
vision::CardColorModel trainCard(const vision::ImageBuffer& frame, vision::Size size)
{
    vision::Pipeline pipeline;
    pipeline.add(std::make_unique<vision::FrameCheckStage>(size, kFormat));
    pipeline.add(std::make_unique<vision::ChromaticityStage>(size));
    auto card = std::make_unique<vision::CardStage>(size);
    vision::CardStage& stage = *card;
    pipeline.add(std::move(card));
    stage.requestTraining(kTrainFraction);
    vision::FrameState state;
    vision::Pipeline::begin(state, {frame.view(), 0, 0});
    pipeline.run(state);
    if (!stage.lastTrainingSucceeded())
        throw std::runtime_error("the card's colour could not be trained on the training frame");
    return stage.tracker().trainedModel();
}

/// The firmware's pipeline with config/mirror.toml's defaults (firmware/src/pipeline_builder.cpp);
/// the AAM stage too when `aam` is given ([faces] model set).
void buildPipeline(const Options& o, const vision::CardColorModel& card,
                   const vision::AamModel* aam, vision::Pipeline& p)
{
    p.add(std::make_unique<vision::FrameCheckStage>(o.size, kFormat));
    p.add(std::make_unique<vision::ChromaticityStage>(o.size));
    auto cardStage = std::make_unique<vision::CardStage>(o.size);
    cardStage->tracker().setModel(card);
    p.add(std::move(cardStage));
    auto motion = std::make_unique<vision::MotionStage>(o.size);
    vision::FaceTrackerOptions faces;
    faces.detector.minSize = {24, 24};
    faces.detectionWindowBudget = 5000;
    auto faceStage =
        std::make_unique<vision::FaceStage>(*motion, vision::loadHaarCascade(o.cascade), faces);
    std::unique_ptr<vision::AamStage> aamStage;
    if (aam != nullptr)
        aamStage = std::make_unique<vision::AamStage>(*motion, *faceStage, *aam);
    p.add(std::move(motion));
    p.add(std::move(faceStage));
    if (aamStage)
        p.add(std::move(aamStage));
}

/// The AAM model at `path` ("" = none); throws with the loader's one line when it is unusable.
std::unique_ptr<vision::AamModel> loadModel(const std::string& path)
{
    if (path.empty())
        return nullptr;
    vision::AamModelFile f = vision::loadAamModel(path);
    if (!f.ok)
        throw std::runtime_error(f.problem);
    return std::make_unique<vision::AamModel>(std::move(f.model));
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        const Options o = parse(argc, argv);
        const std::vector<vision::ImageBuffer> frames = readFrames(o.frames, o.size);
        const vision::CardColorModel card = trainCard(readFrames(o.train, o.size).front(), o.size);
        const std::unique_ptr<vision::AamModel> aam = loadModel(o.model);
        vision::Pipeline pipeline;
        buildPipeline(o, card, aam.get(), pipeline);
        std::printf("stages:");
        for (std::size_t s = 0; s < pipeline.size(); ++s)
            std::printf(" %s", pipeline.stage(s).name());
        const long n = static_cast<long>(frames.size()) - o.skip;
        std::printf("\nframes: %ld\n", n);
        std::fflush(stdout);

        vision::FrameState state;
        for (long i = 0; i < n; ++i) {
            const vision::Frame frame{frames[static_cast<std::size_t>(i + o.skip)].view(),
                                      static_cast<std::uint64_t>(i), i * 33'333'333};
            vision::Pipeline::begin(state, frame);
            for (std::size_t s = 0; s < pipeline.size(); ++s) {
                mirror_arm_mark();
                pipeline.stage(s).process(state);
            }
            mirror_arm_mark();
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vision-frame-loop: %s\n", e.what());
        return 1;
    }
}
