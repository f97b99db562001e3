// The AAM model at start-up (`[faces] model`, §5.3): the pipeline builder reads it; a missing or
// corrupt file is one warning line and the pipeline runs on without the AAM stage (the faces keep
// the 2D pose); a good one adds the "aam" stage after the faces; none configured, nothing said.
#include "../../firmware/src/pipeline_builder.hpp"  // white-box: the builder itself
#include "firmware/log.hpp"
#include "test_paths.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

constexpr const char* kCascade =
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

/// The warning lines logged while building a pipeline for `model`, and what was built.
struct Built {
    std::vector<std::string> warnings;
    firmware::VisionStages stages;
    std::vector<std::string> stageNames;
};

std::vector<std::string> warningLines()
{
    std::vector<std::string> lines;
    firmware::forEachRecentLogLine(
        firmware::kLogRingLines,
        [](const char* line, void* context) {
            static_cast<std::vector<std::string>*>(context)->emplace_back(line);
        },
        &lines, firmware::LogLevel::Warn);
    return lines;
}

Built build(const std::string& model, vision::Pipeline& pipeline)
{
    firmware::Config config;
    config.card.enabled = false;
    config.faces.enabled = true;
    config.faces.cascade = kCascade;
    config.faces.model = model;
    const int devNull = ::open("/dev/null", O_WRONLY);
    firmware::setLogFd(devNull);
    const std::size_t before = warningLines().size();
    Built b;
    b.stages = firmware::buildPipeline(config, {640, 480}, vision::PixelFormat::RGB24, pipeline);
    const std::vector<std::string> after = warningLines();
    // The ring keeps the last lines: what is new is at its end.
    const std::size_t fresh = after.size() >= before ? after.size() - before : after.size();
    b.warnings.assign(after.end() - static_cast<std::ptrdiff_t>(fresh), after.end());
    firmware::setLogFd(2);
    ::close(devNull);
    for (std::size_t i = 0; i < pipeline.size(); ++i)
        b.stageNames.emplace_back(pipeline.stage(i).name());
    return b;
}

class AamModelStartup : public testing::Test {
protected:
    void SetUp() override
    {
        if (!std::filesystem::exists(kCascade))
            GTEST_SKIP() << "no face cascade (opencv-data)";
    }
};

TEST_F(AamModelStartup, NoModelConfiguredNoStageAndNothingSaid)
{
    vision::Pipeline pipeline;
    const Built b = build("", pipeline);
    EXPECT_EQ(b.stages.aam, nullptr);
    EXPECT_NE(b.stages.faces, nullptr);
    EXPECT_TRUE(b.warnings.empty()) << b.warnings.front();
    EXPECT_EQ(b.stageNames.back(), "faces");
}

TEST_F(AamModelStartup, MissingModelIsOneWarningAndTheFacesKeepTheTwoDPose)
{
    vision::Pipeline pipeline;
    const std::string path = testing_support::freshOutputDir("aam_startup_missing") + "/none.aam";
    const Built b = build(path, pipeline);
    EXPECT_EQ(b.stages.aam, nullptr);
    ASSERT_NE(b.stages.faces, nullptr) << "the faces run on";
    EXPECT_EQ(b.stageNames.back(), "faces");
    ASSERT_EQ(b.warnings.size(), 1u);
    EXPECT_NE(b.warnings[0].find("faces: model " + path + ": "), std::string::npos)
        << b.warnings[0];
    EXPECT_NE(b.warnings[0].find("faces keep the 2D pose"), std::string::npos) << b.warnings[0];
}

TEST_F(AamModelStartup, CorruptModelIsOneWarningAndTheFacesKeepTheTwoDPose)
{
    const std::string dir = testing_support::freshOutputDir("aam_startup_corrupt");
    const std::string truncated = dir + "/truncated.aam", garbage = dir + "/garbage.aam";
    std::ofstream(truncated, std::ios::binary) << "MIRRAAM";
    std::ofstream(garbage, std::ios::binary) << std::string(4096, 'x');
    for (const std::string& path : {truncated, garbage}) {
        vision::Pipeline pipeline;
        const Built b = build(path, pipeline);
        EXPECT_EQ(b.stages.aam, nullptr) << path;
        EXPECT_NE(b.stages.faces, nullptr) << path;
        ASSERT_EQ(b.warnings.size(), 1u) << path;
        EXPECT_NE(b.warnings[0].find(path), std::string::npos) << b.warnings[0];
        EXPECT_NE(b.warnings[0].find("faces keep the 2D pose"), std::string::npos) << b.warnings[0];
        EXPECT_EQ(b.warnings[0].find('\n'), b.warnings[0].size() - 1) << "one line";
    }
}

TEST_F(AamModelStartup, GoodModelAddsTheAamStageAfterTheFaces)
{
    const std::string path = testing_support::sourceDir() + "/out/aam/imm-demo.aam";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "out/aam/imm-demo.aam is not built (scripts/dev model)";
    vision::Pipeline pipeline;
    const Built b = build(path, pipeline);
    ASSERT_NE(b.stages.aam, nullptr);
    EXPECT_TRUE(b.warnings.empty()) << b.warnings.front();
    EXPECT_EQ(b.stageNames.back(), "aam");
    EXPECT_EQ(b.stageNames[b.stageNames.size() - 2], "faces");
    EXPECT_GT(b.stages.aam->fitter().vertexCount(), 0);
}

}  // namespace
