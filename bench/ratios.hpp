#pragma once
// mirror-bench --ratios: times the target pairs in one run and prints the raw times, then one
// line per target (speed-ups: higher is better):
//   ratio chroma_vs_opencv_exact <x>   OpenCV's faster exact float formulation / ours
//   ratio chroma_vs_seed_lut <x>       the dissertation's Table 5 loop (-O3) / ours
//   ratio card_tracker_ms <ms>         median ms per 720x480 frame: chromaticity + process
// and for the faces (§3, FaceCases):
//   ratio vj_vs_opencv <x>             cv::CascadeClassifier / our FaceDetector, 360x240, default
//   ratio mog_vs_mog2 <x>              cv::BackgroundSubtractorMOG2 / our MotionDetector, K=3
//   ratio lk_vs_opencv <x>             OpenCV pyramid + LK / ours, 50 points, 3 levels
//   ratio face_pipeline_mean_ms <ms>   motion + face stages per FGNet 720x576 frame, mean
//   ratio face_pipeline_p99_ms <ms>    the same, 99th percentile
// and for the overlays (§6, OverlayRenderCase):
//   ratio render_3faces_ms <ms>        thread CPU ms the 3D overlays of 3 faces add to a 1280x720
//                                      frame (llvmpipe on the calling thread), median

#include <string>

namespace bench {

class ChromaticityCases;
class CardTrackerCase;
class FaceCases;

void printRatios(ChromaticityCases& chroma, CardTrackerCase& card);
void printFaceRatios(FaceCases& faces);
/// Loads the catalogue (e.g. assets/overlays/catalogue.toml), times the overlay case and prints
/// its raw times and `ratio render_3faces_ms`. Throws std::runtime_error (no GL, bad catalogue).
void printRenderRatios(const std::string& catalogueToml);

}  // namespace bench
