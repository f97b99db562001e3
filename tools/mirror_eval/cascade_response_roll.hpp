#pragma once
// Roll of a detected face from the Haar cascade's own response (mirror-eval roll's independent
// check on the truth, not a product estimator): a frontal cascade is trained on upright faces and
// passes fewer and fewer windows as the face turns in the image plane, so the angle that best
// warps the face upright is where its raw hits peak. It shares nothing with image symmetry but
// the pixels, so the two err independently, which is what the truth-noise estimate needs.

#include "vision/face_detector.hpp"
#include "vision/geometry.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/image.hpp"

namespace mirror_eval {

class CascadeResponseRoll {
public:
    /// Sizes the patch and its detector (a tool: may throw on a cascade it cannot evaluate).
    explicit CascadeResponseRoll(const vision::HaarCascade& cascade);

    /// Roll (degrees, RollEstimate's sense) of the face in the detector box centred on `centre`
    /// (continuous coordinates, as warpUpright) with side `boxSize`: for each angle in
    /// [-55, 55] degrees in 2.5 degree steps, the square of 1.6 box sides about the centre is
    /// warped upright by it into a 48 px patch and the cascade's raw hits there counted (scale
    /// factor 1.05, every position, no grouping); the roll is the hit-weighted mean angle over
    /// the run of angles about the peak that keep at least 30% of the peak count. 0 when no
    /// angle has a hit.
    double estimate(const vision::ConstImageView& gray, vision::Point2f centre, float boxSize);

private:
    vision::FaceDetector detector_;
    vision::ImageBuffer patch_;
};

}  // namespace mirror_eval
