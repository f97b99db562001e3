// colorlab as a program: the light-ramp recording with a known answer, real frames, and the
// errors (one clear line, exit 1 for input, 2 for usage and samples).
#include "experiment.hpp"
#include "ramp_generator.hpp"
#include "run_colorlab.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using colorlab_test::runColorlab;

std::string shq(const std::string& s)
{
    return "'" + s + "'";
}

std::string lastLine(const std::string& path)
{
    std::ifstream in(path);
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty())
            last = line;
    return last;
}

/// Position of each space in a `ranking: a > b > ...` line.
std::map<std::string, int> positions(const std::string& line)
{
    std::map<std::string, int> pos;
    std::istringstream words(line.substr(line.find(':') + 1));
    int i = 0;
    for (std::string w; words >> w;)
        if (w != ">")
            pos[w] = i++;
    return pos;
}

void expectTablesAndPlots(const std::string& out, const std::vector<std::string>& sampleNames)
{
    for (const char* f : {"stdev.csv", "stdev.txt", "dp.csv", "dp.txt", "ranking.txt",
                          "saturated.txt", "plots/summary.png"})
        EXPECT_TRUE(fs::is_regular_file(out + "/" + f)) << f;
    for (const auto& info : vision::colorSpaces()) {
        EXPECT_GT(fs::file_size(out + "/plots/series_" + info.name + ".png"), 1000u) << info.name;
        EXPECT_GT(fs::file_size(out + "/plots/dp_" + info.name + ".png"), 1000u) << info.name;
        for (const auto& s : sampleNames)
            EXPECT_TRUE(fs::is_regular_file(out + "/series/" + s + "_" + info.name + ".csv"))
                << s << " " << info.name;
    }
}

TEST(ColorlabRamp, ChromaticityRanksAboveYiqHsvHls)
{
    // Generated through the library at a small size (quick), analysed by the binary.
    const auto dir = testing_support::freshOutputDir("colorlab_ramp");
    colorlab::RampOptions ramp;
    ramp.outDir = dir + "/frames";
    ramp.frames = 40;
    ramp.width = 192;
    ramp.height = 128;
    colorlab::generateRamp(ramp);
    ASSERT_TRUE(fs::is_regular_file(ramp.outDir + "/frame_0039.png"));
    ASSERT_TRUE(fs::is_regular_file(ramp.outDir + "/samples.txt"));

    const auto out = dir + "/out";
    const auto run =
        runColorlab(shq(ramp.outDir) + " --samples " + shq(ramp.outDir + "/samples.txt") +
                    " --out " + shq(out) + " --exclude-saturated");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string line = lastLine(out + "/ranking.txt");
    ASSERT_EQ(line.rfind("ranking: ", 0), 0u) << line;
    EXPECT_NE(run.output.find(line), std::string::npos) << "ranking printed too";
    auto pos = positions(line);
    ASSERT_EQ(pos.size(), static_cast<std::size_t>(vision::kColorSpaceCount)) << line;
    EXPECT_LT(pos["chromaticity"], pos["yiq"]) << line;
    EXPECT_LT(pos["chromaticity"], pos["hsv"]) << line;
    EXPECT_LT(pos["chromaticity"], pos["hls"]) << line;
    EXPECT_LT(pos["c1c2c3"], pos["yiq"]) << line;
    EXPECT_LT(pos["chromaticity"], pos["rgb"]) << line;
    // The light ramp reaches 1.6x: the bright papers clip, and those frames were left out.
    EXPECT_NE(run.output.find("saturated (excluded)"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find(" 0 saturated"), std::string::npos) << run.output;
    expectTablesAndPlots(out,
                         {"orange", "red", "green", "blue", "yellow", "brown", "beige", "black"});
}

TEST(ColorlabRamp, GenerateSubcommandWritesFramesAndSamples)
{
    const auto dir = testing_support::freshOutputDir("colorlab_generate");
    const auto run = runColorlab(std::string("generate --out ") + shq(dir) + " --frames 3");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    for (const char* f : {"frame_0000.png", "frame_0002.png", "samples.txt", "illumination.csv"})
        EXPECT_TRUE(fs::is_regular_file(dir + "/" + f)) << f;
    EXPECT_FALSE(fs::exists(dir + "/frame_0003.png"));
    // The ramp is a triangle: full light at both ends, the minimum in the middle.
    colorlab::RampOptions o;
    o.frames = 5;
    EXPECT_DOUBLE_EQ(colorlab::rampGain(o, 0), 1.6);
    EXPECT_DOUBLE_EQ(colorlab::rampGain(o, 2), 0.2);
    EXPECT_DOUBLE_EQ(colorlab::rampGain(o, 4), 1.6);
}

TEST(ColorlabReal, FgnetFramesWithAGridAndASampleFile)
{
    const auto frames = testing_support::sharedData("fgnet_talking_face/images/franck_0000*.jpg");
    const auto dir = testing_support::freshOutputDir("colorlab_fgnet");
    auto run = runColorlab(shq(frames) + " --grid 3x2 --radius 4 --out " + shq(dir + "/grid") +
                           " --max-frames 6");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("6 samples, 6 of 6 frames used"), std::string::npos) << run.output;
    EXPECT_EQ(lastLine(dir + "/grid/ranking.txt").rfind("ranking: ", 0), 0u);
    expectTablesAndPlots(dir + "/grid", {"r0c0", "r1c2"});

    // Points on the 720x576 talking-face frames: background, face, shirt.
    std::ofstream(dir + "/samples.txt") << "# name x y [radius]\nwall 60 60\nface 360 250 5\n"
                                           "shirt 360 540 6\n";
    run = runColorlab(shq(frames) + " --samples samples.txt --out out --no-plots", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    for (const char* f : {"stdev.csv", "stdev.txt", "dp.csv", "dp.txt", "ranking.txt"})
        EXPECT_TRUE(fs::is_regular_file(dir + "/out/" + f)) << f;
    EXPECT_FALSE(fs::exists(dir + "/out/plots"));
    // 3 samples: 3 pairs, a header and one row per pair.
    std::ifstream dp(dir + "/out/dp.csv");
    int lines = 0;
    for (std::string l; std::getline(dp, l);)
        ++lines;
    EXPECT_EQ(lines, 4);
}

TEST(ColorlabReal, VideoFile)
{
    const auto video = testing_support::sharedData("opencv_samples_video/Megamind.avi");
    const auto dir = testing_support::freshOutputDir("colorlab_video");
    const auto run =
        runColorlab(shq(video) + " --grid 2x2 --max-frames 8 --no-plots --out " + shq(dir));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("4 samples, 8 of 8 frames used"), std::string::npos) << run.output;
    EXPECT_EQ(lastLine(dir + "/ranking.txt").rfind("ranking: ", 0), 0u);
    std::ifstream series(dir + "/series/r1c1_chromaticity.csv");
    std::string header;
    std::getline(series, header);
    EXPECT_EQ(header, "frame,r,g,b,saturated");
}

TEST(ColorlabErrors, MissingInputIsOneLineAndExit1)
{
    const auto dir = testing_support::freshOutputDir("colorlab_err_input");
    const auto run =
        runColorlab(shq(dir + "/no-such.avi") + " --grid 2x2 --out " + shq(dir + "/out"));
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_EQ(run.output, "colorlab: file:" + dir + "/no-such.avi: no such file or directory\n");
    EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(ColorlabErrors, SampleOutsideTheFrameNamesFileLineAndFrame)
{
    const auto frames = testing_support::sharedData("fgnet_talking_face/images/franck_00000.jpg");
    const auto dir = testing_support::freshOutputDir("colorlab_err_outside");
    std::ofstream(dir + "/samples.txt") << "# hand-picked\nwall 60 60\nskin 900 20\n";
    const auto run = runColorlab(shq(frames) + " --samples samples.txt --out out", dir);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_EQ(run.output,
              "samples.txt:3: sample 'skin' at (900, 20) is outside the 720x576 frame\n");
}

TEST(ColorlabErrors, UnreadableEmptyOrMissingSamplesAreExit2)
{
    const auto frames = testing_support::sharedData("fgnet_talking_face/images/franck_00000.jpg");
    const auto dir = testing_support::freshOutputDir("colorlab_err_samples");
    auto run = runColorlab(shq(frames) + " --samples nothing.txt --out out", dir);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_EQ(run.output, "nothing.txt: cannot read sample list: No such file or directory\n");

    std::ofstream(dir + "/empty.txt") << "# no samples yet\n";
    run = runColorlab(shq(frames) + " --samples empty.txt --out out", dir);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_EQ(run.output, "empty.txt: no samples (lines `name x y [radius]`)\n");

    run = runColorlab(shq(frames) + " --out out", dir);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_EQ(run.output, "no samples: give a sample list (--samples FILE) or --grid NxM\n");

    run = runColorlab(shq(frames) + " --grid 3 --out out", dir);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_EQ(run.output, "--grid 3: expected NxM with N and M in 1..64, e.g. 4x2\n");
}

TEST(ColorlabErrors, UsageIsExit2)
{
    auto run = runColorlab("");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("need INPUT and --out DIR"), std::string::npos) << run.output;
    run = runColorlab("x --bogus");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    run = runColorlab("--help");
    EXPECT_EQ(run.exitCode, 0) << run.output;
}

}  // namespace
