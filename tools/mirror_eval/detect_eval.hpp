#pragma once
// mirror-eval detect: our Viola-Jones FaceDetector on the CMU/MIT frontal sets against their
// 6-point ground truth (face_match.hpp's rule) and against cv::CascadeClassifier with the same
// cascade and parameters (identical boxes). Images run at full size.

#include <cstdio>
#include <string>

namespace mirror_eval {

inline constexpr const char* kDefaultCascade =
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

struct DetectEvalOptions {
    std::string images;  ///< folder of the images named in the truth file
    std::string truth;   ///< landmarks_test_set_?.txt
    std::string cascade = kDefaultCascade;
    double scaleFactor = 1.1;
    int minNeighbors = 3;
    int minSize = 0;       ///< smallest box side (0: the cascade's window)
    int maxImages = 0;     ///< 0: all images of the truth file; else the first N (tests)
    bool perImage = true;  ///< print one line per image
};

/// Runs, prints the report and the final line `detect: precision=.. recall=.. agree_opencv=..`
/// to `out`. Returns the exit code; errors go to `err` as one line.
int runDetectEval(const DetectEvalOptions& options, std::FILE* out, std::FILE* err);

}  // namespace mirror_eval
