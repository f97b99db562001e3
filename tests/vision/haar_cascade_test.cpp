// The cascade XML reader on OpenCV's own cascade files (Debian's opencv-data) and on broken
// files written here: each problem is one clear line naming the file and the line.
#include "vision/haar_cascade.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace vision;

namespace {

const std::string kDefault = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";
const std::string kAlt2 = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_alt2.xml";

std::string readAll(const std::string& path)
{
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string writeFile(const std::string& name, const std::string& text)
{
    // One folder per test: ctest runs the tests of this file as parallel processes.
    const std::string dir = testing_support::freshOutputDir(
        std::string("haar_cascade_test/") +
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
}

// The error of loading `path`, or "" when it loads.
std::string loadError(const std::string& path)
{
    try {
        loadHaarCascade(path);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

TEST(HaarCascade, ReadsOpenCvDefaultFrontalFaceCascade)
{
    if (!std::filesystem::exists(kDefault))
        GTEST_SKIP() << "opencv-data not installed";
    const HaarCascade c = loadHaarCascade(kDefault);
    EXPECT_EQ(c.windowWidth, 24);
    EXPECT_EQ(c.windowHeight, 24);
    ASSERT_EQ(c.stages.size(), 25u);
    EXPECT_EQ(c.stages[0].weakCount, 9);
    EXPECT_FLOAT_EQ(c.stages[0].threshold, -5.0425500869750977f);
    EXPECT_TRUE(c.stumpsOnly());
    EXPECT_EQ(c.features.size(), 2913u);
    EXPECT_EQ(c.weak.size(), 2913u);
    EXPECT_EQ(c.leaves.size(), 2 * c.weak.size());
    // The first feature: "6 4 12 9 -1." and "6 7 12 3 3.".
    const HaarFeature& f = c.features[0];
    ASSERT_EQ(f.rectCount, 2);
    EXPECT_EQ(f.rects[0].x, 6);
    EXPECT_EQ(f.rects[0].width, 12);
    EXPECT_EQ(f.rects[0].height, 9);
    EXPECT_EQ(f.rects[0].weight, -1.0f);
    EXPECT_EQ(f.rects[1].y, 7);
    EXPECT_EQ(f.rects[1].weight, 3.0f);
    // The last feature has three rectangles.
    EXPECT_EQ(c.features.back().rectCount, 3);
    // Stump children: left leaf 0, right leaf 1.
    EXPECT_EQ(c.nodes[0].left, 0);
    EXPECT_EQ(c.nodes[0].right, -1);
}

TEST(HaarCascade, ReadsTreesOfAlt2Cascade)
{
    if (!std::filesystem::exists(kAlt2))
        GTEST_SKIP() << "opencv-data not installed";
    const HaarCascade c = loadHaarCascade(kAlt2);
    EXPECT_EQ(c.windowWidth, 20);
    EXPECT_EQ(c.stages.size(), 20u);
    EXPECT_FALSE(c.stumpsOnly());
    EXPECT_EQ(c.stages[0].weakCount, 3);
    // "0 1 0 4.3272329494357109e-03 -1 -2 1 1.3076160103082657e-02": node 0 goes to leaf 0 or
    // node 1, node 1 to leaves 1 and 2.
    const HaarWeakClassifier& w = c.weak[0];
    EXPECT_EQ(w.nodeCount, 2);
    EXPECT_EQ(c.nodes[0].left, 0);
    EXPECT_EQ(c.nodes[0].right, 1);
    EXPECT_EQ(c.nodes[1].featureIndex, 1);
    EXPECT_EQ(c.nodes[1].right, -2);
    EXPECT_FLOAT_EQ(c.leaves[2], 2.6293140649795532e-01f);
}

TEST(HaarCascade, MissingFileIsOneClearLine)
{
    const std::string e = loadError("/nonexistent/cascade.xml");
    EXPECT_EQ(e, "cascade /nonexistent/cascade.xml: cannot read file: No such file or directory");
}

TEST(HaarCascade, ADeviceOrFifoIsRefusedBeforeAnyRead)
{
    // /dev/zero would be read for ever; a FIFO without a writer would block the start-up.
    EXPECT_EQ(loadError("/dev/zero"),
              "cascade /dev/zero: not a regular file (a FIFO, a device or a socket)");
    const std::string fifo = writeFile("placeholder", "") + ".fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(loadError(fifo),
              "cascade " + fifo + ": not a regular file (a FIFO, a device or a socket)");
}

TEST(HaarCascade, DeepNestingIsRefusedNotAStackOverflow)
{
    std::string text;
    for (int i = 0; i < 50000; ++i)
        text += "<a>";
    const std::string e = loadError(writeFile("deep.xml", text));
    EXPECT_NE(e.find(": line 1: elements nested deeper than 32 levels"), std::string::npos) << e;
}

// A cascade of one feature whose window is W x H and whose first rectangle is `rect`.
std::string oneFeatureCascade(int width, int height, const std::string& rect)
{
    return "<opencv_storage><cascade><stageType>BOOST</stageType><featureType>HAAR</featureType>\n"
           "<height>" + std::to_string(height) + "</height><width>" + std::to_string(width) +
           "</width>\n<features><_><rects><_>" + rect + "</_><_>0 0 1 2 2.</_></rects></_>"
           "</features>\n<stages></stages></cascade></opencv_storage>\n";
}

TEST(HaarCascade, SizesThatWouldOverflowAreRefusedByName)
{
    const std::string wide =
        writeFile("wide.xml", oneFeatureCascade(24, 24, "1 0 2147483647 4 -1."));
    EXPECT_NE(loadError(wide).find(": line 3: rectangle outside the detection window"),
              std::string::npos)
        << loadError(wide);
    const std::string far = writeFile("far.xml", oneFeatureCascade(24, 24, "2147483647 0 4 4 -1."));
    EXPECT_NE(loadError(far).find("rectangle outside the detection window"), std::string::npos)
        << loadError(far);
    const std::string huge = writeFile("huge.xml", oneFeatureCascade(100000, 24, "0 0 2 2 -1."));
    EXPECT_NE(loadError(huge).find("window larger than 64x64"), std::string::npos)
        << loadError(huge);
}

TEST(HaarCascade, TruncatedFileNamesTheLine)
{
    if (!std::filesystem::exists(kDefault))
        GTEST_SKIP() << "opencv-data not installed";
    const std::string text = readAll(kDefault);
    const std::string path = writeFile("truncated.xml", text.substr(0, text.size() / 2));
    const std::string e = loadError(path);
    EXPECT_NE(e.find("cascade " + path + ": line "), std::string::npos) << e;
    EXPECT_NE(e.find("end of file"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos);
}

TEST(HaarCascade, WrongRootAndMissingStagesAreReported)
{
    const std::string wrongRoot = writeFile("wrong_root.xml",
                                            "<?xml version=\"1.0\"?>\n<html>\n"
                                            "<body>not a cascade</body></html>\n");
    EXPECT_NE(loadError(wrongRoot).find(": line 2: expected <opencv_storage>"), std::string::npos)
        << loadError(wrongRoot);

    const std::string noStages =
        writeFile("no_stages.xml",
                  "<opencv_storage>\n<cascade type_id=\"opencv-cascade-classifier\">\n"
                  "<stageType>BOOST</stageType><featureType>HAAR</featureType>\n"
                  "<height>24</height><width>24</width>\n"
                  "<features><_><rects><_>0 0 2 2 -1.</_><_>0 0 1 2 2.</_></rects></_>"
                  "</features>\n</cascade></opencv_storage>\n");
    EXPECT_NE(loadError(noStages).find(": line 2: expected <stages> in <cascade>"),
              std::string::npos)
        << loadError(noStages);

    const std::string mismatched =
        writeFile("mismatched.xml", "<opencv_storage>\n<cascade>\n</stages>\n</opencv_storage>\n");
    EXPECT_NE(loadError(mismatched).find(": line 3: expected </cascade>"), std::string::npos)
        << loadError(mismatched);

    const std::string badNumber = writeFile(
        "bad_number.xml",
        "<opencv_storage><cascade><stageType>BOOST</stageType><featureType>HAAR</featureType>\n"
        "<height>2x4</height><width>24</width></cascade></opencv_storage>\n");
    EXPECT_NE(loadError(badNumber).find(": line 2: expected an integer in <height>"),
              std::string::npos)
        << loadError(badNumber);

    const std::string lbp = writeFile(
        "lbp.xml",
        "<opencv_storage><cascade><stageType>BOOST</stageType><featureType>LBP</featureType>"
        "</cascade></opencv_storage>\n");
    EXPECT_NE(loadError(lbp).find("expected featureType HAAR, found LBP"), std::string::npos);

    const std::string empty = writeFile("empty.xml", "");
    EXPECT_NE(loadError(empty).find("line 1: expected an XML element"), std::string::npos);
}

}  // namespace
