#include "platform/headless_display.hpp"

#include "alloc_counter.hpp"
#include "test_paths.hpp"

#include <GLES2/gl2.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <utility>

namespace {

using platform::HeadlessDisplay;

constexpr int kWidth = 320;
constexpr int kHeight = 240;

bool exists(const std::string& path)
{
    return std::filesystem::exists(path);
}

std::string snapshotName(const std::string& dir, int frame)
{
    char name[64];
    std::snprintf(name, sizeof name, "/snapshot-%06d.png", frame);
    return dir + name;
}

bool clearFrame(HeadlessDisplay& display, float r, float g, float b)
{
    if (!display.beginFrame())
        return false;
    glClearColor(r, g, b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    return display.present();
}

// Pixel of a PNG as R,G,B.
cv::Vec3b rgbAt(const cv::Mat& bgr, int x, int y)
{
    const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
    return {p[2], p[1], p[0]};
}

void expectNear(cv::Vec3b actual, int r, int g, int b, const std::string& where)
{
    EXPECT_NEAR(actual[0], r, 1) << where;
    EXPECT_NEAR(actual[1], g, 1) << where;
    EXPECT_NEAR(actual[2], b, 1) << where;
}

std::string constructionError(const std::string& dir)
{
    try {
        HeadlessDisplay display(dir, kWidth, kHeight, 0);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

TEST(HeadlessDisplay, DescribesItself)
{
    const std::string dir = testing_support::freshOutputDir("headless_display/describe");
    HeadlessDisplay display(dir, kWidth, kHeight, 0);
    EXPECT_EQ(display.width(), kWidth);
    EXPECT_EQ(display.height(), kHeight);
    EXPECT_STREQ(display.outputDir(), dir.c_str());
    EXPECT_STREQ(display.lastSnapshot(), "");
    const std::string description = display.description();
    EXPECT_EQ(description.rfind("headless:" + dir + " (320x240, ", 0), 0u) << description;
    EXPECT_GT(description.size(), ("headless:" + dir + " (320x240, )").size()) << "no renderer";
}

TEST(HeadlessDisplay, WritesEveryNthFrameWithTheClearedColour)
{
    const std::string dir = testing_support::freshOutputDir("headless_display/every5");
    HeadlessDisplay display(dir, kWidth, kHeight, 5);
    for (int frame = 0; frame < 12; ++frame)
        ASSERT_TRUE(clearFrame(display, 0.2f, 0.4f, 0.8f)) << display.lastError();
    EXPECT_EQ(display.framesPresented(), 12);

    for (int frame = 0; frame < 12; ++frame) {
        const std::string path = snapshotName(dir, frame);
        EXPECT_EQ(exists(path), frame % 5 == 0) << path;
    }
    EXPECT_EQ(display.lastSnapshot(), snapshotName(dir, 10));
    for (int frame : {0, 5, 10}) {
        const std::string path = snapshotName(dir, frame);
        const cv::Mat png = cv::imread(path, cv::IMREAD_UNCHANGED);
        ASSERT_FALSE(png.empty()) << path;
        ASSERT_EQ(png.type(), CV_8UC3) << "snapshots are RGB";
        ASSERT_EQ(png.cols, kWidth);
        ASSERT_EQ(png.rows, kHeight);
        for (const auto& [x, y] : {std::pair{0, 0}, std::pair{kWidth - 1, kHeight - 1},
                                   std::pair{kWidth / 2, kHeight / 3}})
            expectNear(rgbAt(png, x, y), 51, 102, 204, path);
    }
    EXPECT_FALSE(exists(snapshotName(dir, 10) + ".tmp"));
}

TEST(HeadlessDisplay, RequestedSnapshotIsTheNextFrame)
{
    const std::string dir = testing_support::freshOutputDir("headless_display/request");
    HeadlessDisplay display(dir, kWidth, kHeight, 0);
    for (int frame = 0; frame < 3; ++frame)
        ASSERT_TRUE(clearFrame(display, 0.0f, 0.0f, 0.0f));
    EXPECT_STREQ(display.lastSnapshot(), "");
    EXPECT_TRUE(display.requestSnapshot());
    ASSERT_TRUE(clearFrame(display, 1.0f, 0.0f, 0.0f)) << display.lastError();
    ASSERT_TRUE(clearFrame(display, 0.0f, 1.0f, 0.0f));
    EXPECT_EQ(display.lastSnapshot(), snapshotName(dir, 3));
    EXPECT_FALSE(exists(snapshotName(dir, 4))) << "a request gives one snapshot";
    const cv::Mat png = cv::imread(snapshotName(dir, 3), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(png.empty());
    expectNear(rgbAt(png, 10, 10), 255, 0, 0, "requested frame");
}

GLuint compile(GLenum type, const char* source)
{
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    EXPECT_EQ(ok, GL_TRUE);
    return shader;
}

TEST(HeadlessDisplay, QuadInTheTopHalfIsInTheTopHalfOfThePng)
{
    const std::string dir = testing_support::freshOutputDir("headless_display/orientation");
    HeadlessDisplay display(dir, kWidth, kHeight, 1);
    ASSERT_TRUE(display.hasStencil()) << "Mesa offers OES_packed_depth_stencil";
    ASSERT_TRUE(display.beginFrame()) << display.lastError();

    const GLuint program = glCreateProgram();
    glAttachShader(program, compile(GL_VERTEX_SHADER,
                                    "attribute vec2 p;\n"
                                    "void main() { gl_Position = vec4(p, 0, 1); }"));
    glAttachShader(program, compile(GL_FRAGMENT_SHADER,
                                    "precision mediump float;\n"
                                    "void main() { gl_FragColor = vec4(1, 1, 0, 1); }"));
    glBindAttribLocation(program, 0, "p");
    glLinkProgram(program);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    ASSERT_EQ(linked, GL_TRUE);
    // Normalised device y from 0 to 1 is the upper half of the picture.
    const GLfloat quad[] = {-1, 0, 1, 0, -1, 1, 1, 1};
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(program);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, quad);
    glEnableVertexAttribArray(0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    ASSERT_TRUE(display.present()) << display.lastError();
    glDeleteProgram(program);

    const cv::Mat png = cv::imread(snapshotName(dir, 0), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(png.empty());
    expectNear(rgbAt(png, kWidth / 2, 2), 255, 255, 0, "top row");
    expectNear(rgbAt(png, kWidth / 2, kHeight / 2 - 2), 255, 255, 0, "just above the middle");
    expectNear(rgbAt(png, kWidth / 2, kHeight / 2 + 2), 0, 0, 255, "just below the middle");
    expectNear(rgbAt(png, kWidth / 2, kHeight - 2), 0, 0, 255, "bottom row");
}

TEST(HeadlessDisplay, FramesWithSnapshotsDoNotAllocateInOurCode)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    const std::string dir = testing_support::freshOutputDir("headless_display/allocations");
    HeadlessDisplay display(dir, kWidth, kHeight, 2);
    ASSERT_TRUE(clearFrame(display, 0.5f, 0.5f, 0.5f));  // warm up the driver

    testing_support::AllocationCounts counts;
    bool ok = true;
    {
        testing_support::AllocationScope scope;
        for (int frame = 0; frame < 4; ++frame)
            ok = clearFrame(display, 0.1f * frame, 0.5f, 0.5f) && ok;
        ok = display.requestSnapshot() && clearFrame(display, 0.0f, 0.0f, 0.0f) && ok;
        counts = scope.counts();
    }
    ASSERT_TRUE(ok) << display.lastError();
    EXPECT_EQ(display.lastSnapshot(), snapshotName(dir, 5));
    // The Mesa driver allocates internally (foreign); our code and libpng (arena) must not.
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}

TEST(HeadlessDisplay, PresentWithoutBeginFrameFails)
{
    const std::string dir = testing_support::freshOutputDir("headless_display/order");
    HeadlessDisplay display(dir, kWidth, kHeight, 1);
    EXPECT_FALSE(display.present());
    EXPECT_STRNE(display.lastError(), "");
    EXPECT_EQ(display.framesPresented(), 0);
}

TEST(HeadlessDisplay, CreatesMissingParents)
{
    const std::string base = testing_support::freshOutputDir("headless_display/parents");
    const std::string dir = base + "/a/b/c";
    HeadlessDisplay display(dir + "/", kWidth, kHeight, 1);
    EXPECT_TRUE(std::filesystem::is_directory(dir));
    EXPECT_STREQ(display.outputDir(), dir.c_str());
    ASSERT_TRUE(clearFrame(display, 0, 0, 0)) << display.lastError();
    EXPECT_TRUE(exists(snapshotName(dir, 0)));
    // Only the snapshot: the writability probe is gone.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                            std::filesystem::directory_iterator()),
              1);
}

TEST(HeadlessDisplay, TwoDisplaysShareTheEglDisplay)
{
    const std::string dirA = testing_support::freshOutputDir("headless_display/two-a");
    const std::string dirB = testing_support::freshOutputDir("headless_display/two-b");
    auto first = std::make_unique<HeadlessDisplay>(dirA, kWidth, kHeight, 1);
    HeadlessDisplay second(dirB, 64, 32, 1);
    ASSERT_TRUE(clearFrame(*first, 1, 0, 0)) << first->lastError();
    first.reset();  // must not terminate the EGL display under the second one
    ASSERT_TRUE(clearFrame(second, 0, 1, 0)) << second.lastError();
    const cv::Mat png = cv::imread(snapshotName(dirB, 0), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(png.empty());
    EXPECT_EQ(png.cols, 64);
    expectNear(rgbAt(png, 3, 3), 0, 255, 0, "second display");
}

TEST(HeadlessDisplay, RefusesANewFolderAtTheTopOfTheFileSystem)
{
    const std::string e = constructionError("/unwritable-xyz");
    EXPECT_EQ(e,
              "headless display: /unwritable-xyz does not exist and will not be created at the "
              "top of the file system");
    EXPECT_FALSE(exists("/unwritable-xyz"));

    const std::string nested = constructionError("/ouput-xyz/x");
    EXPECT_TRUE(contains(nested, "/ouput-xyz does not exist")) << nested;
    EXPECT_TRUE(contains(nested, "/ouput-xyz/x")) << nested;
    EXPECT_FALSE(exists("/ouput-xyz"));
}

TEST(HeadlessDisplay, UnusableFoldersThrowWithTheReason)
{
    const std::string proc = constructionError("/proc/mirror-test");
    EXPECT_TRUE(contains(proc, "headless display: cannot create output folder /proc/mirror-test: "))
        << proc;

    const std::string base = testing_support::freshOutputDir("headless_display/file");
    const std::string file = base + "/plain-file";
    std::ofstream(file) << "not a folder";
    const std::string notDir = constructionError(file);
    EXPECT_EQ(notDir, "headless display: output folder " + file + " exists and is not a directory");
    const std::string below = constructionError(file + "/sub");
    EXPECT_TRUE(contains(below, "cannot create output folder " + file + "/sub: ")) << below;
}

TEST(HeadlessDisplay, RejectsInvalidSize)
{
    const std::string dir = testing_support::freshOutputDir("headless_display/size");
    EXPECT_THROW(HeadlessDisplay(dir, 0, 240, 1), std::runtime_error);
}

}  // namespace
