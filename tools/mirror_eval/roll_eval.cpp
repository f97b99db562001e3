#include "roll_eval.hpp"

#include "cascade_response_roll.hpp"
#include "detect_eval.hpp"
#include "error_stats.hpp"
#include "face_match.hpp"
#include "face_truth.hpp"
#include "vision/corner_detector.hpp"
#include "vision/face_detector.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/roll_by_image_symmetry.hpp"
#include "vision/roll_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace mirror_eval {

namespace {

struct Crop {
    cv::Mat gray;
    std::array<vision::Point2f, 3> axis{};  ///< eye midpoint, nose, mouth centre in the crop
    double rotation = 0.0;
};

/// The protocol's crop: side 3x the eye-mouth distance about the face centre, rotated about it by
/// `rotation` degrees (clockwise on screen, our roll sense), border replicated; resampled up to
/// `minSide` when smaller.
Crop makeCrop(const cv::Mat& image, const LandmarkFace& face, double rotation, int minSide)
{
    const vision::Point2f c = face.centre();
    const double d = face.eyeMouthDistance();
    int side = static_cast<int>(std::lround(3.0 * d));
    double scale = 1.0;
    if (minSide > 0 && side < minSide) {
        scale = static_cast<double>(minSide) / (3.0 * d);
        side = minSide;
    }
    // OpenCV's positive angle is anticlockwise on screen; ours is clockwise.
    cv::Mat m = cv::getRotationMatrix2D(cv::Point2f(c.x, c.y), -rotation, scale);
    m.at<double>(0, 2) += 0.5 * (side - 1) - c.x;
    m.at<double>(1, 2) += 0.5 * (side - 1) - c.y;
    Crop crop;
    crop.rotation = rotation;
    cv::warpAffine(image, crop.gray, m, cv::Size(side, side), cv::INTER_LINEAR,
                   cv::BORDER_REPLICATE);
    const vision::Point2f in[3] = {face.eyeMidpoint(), face.nose, face.mouthCentre};
    for (int k = 0; k < 3; ++k) {
        crop.axis[static_cast<std::size_t>(k)] = {
            static_cast<float>(m.at<double>(0, 0) * in[k].x + m.at<double>(0, 1) * in[k].y +
                               m.at<double>(0, 2)),
            static_cast<float>(m.at<double>(1, 0) * in[k].x + m.at<double>(1, 1) * in[k].y +
                               m.at<double>(1, 2))};
    }
    return crop;
}

/// Each detected face's roll before the crop's rotation (a measured roll minus the known
/// rotation), four ways: what the truth-noise estimate compares.
struct UnrotatedRolls {
    std::vector<double> axis, eyeLine, image, cascade;
};

/// The truth's own noise, by the three-cornered hat: the faces' unrotated rolls measured by the
/// annotation (axis, eye line) and by the image (symmetry, cascade response) share only the
/// faces' real roll, so their covariances estimate its spread and what each variance has beyond
/// that is its own noise. The annotated axis of faces 13-20 px from eyes to mouth turns out
/// noisy enough to cap what any estimator can score against it. `u` holds the faces whose two image
/// estimates agree within 10 degrees: a gross failure of either would swamp the covariances, and
/// the choice does not look at the annotation.
void printTruthNoise(const UnrotatedRolls& u, std::FILE* out)
{
    const std::vector<double>* rows[] = {&u.axis, &u.eyeLine, &u.image, &u.cascade};
    const char* names[] = {"axis truth", "eye-line truth", "image symmetry", "cascade response"};
    std::fprintf(out,
                 "truth noise: the roll of each face before the rotation (a roll less the known "
                 "rotation) measured four ways, over the %zu faces whose image estimates agree "
                 "within 10 deg; covariances (deg^2):\n%-18s",
                 u.axis.size(), "");
    for (const char* n : names)
        std::fprintf(out, " %16s", n);
    std::fprintf(out, "\n");
    for (std::size_t i = 0; i < 4; ++i) {
        std::fprintf(out, "%-18s", names[i]);
        for (std::size_t j = 0; j < 4; ++j)
            std::fprintf(out, " %16.2f", covarianceOf(*rows[i], *rows[j]));
        std::fprintf(out, "\n");
    }
    // The faces' real roll spread, from each pair of measurements whose errors should be
    // independent: the annotator's clicks against either image method, and the two image
    // methods, which share only the pixels (any error they share inflates their covariance: the
    // generous end). Each gives a truth noise; the range is what an exact estimator could score.
    const double axisVariance = covarianceOf(u.axis, u.axis);
    const std::pair<const char*, double> real[] = {
        {"axis-image", covarianceOf(u.axis, u.image)},
        {"axis-cascade", covarianceOf(u.axis, u.cascade)},
        {"image-cascade", covarianceOf(u.image, u.cascade)}};
    // Two ways to turn a noise into what an exact estimator would score (within 5 degrees of
    // this truth): a Gaussian of that sd, and our own errors (truth less image symmetry) scaled
    // down by sd / their sd, which keeps their heavier-than-Gaussian tails.
    std::vector<double> ours;
    for (std::size_t i = 0; i < u.axis.size(); ++i)
        ours.push_back(u.axis[i] - u.image[i]);
    const double oursSd = std::sqrt(covarianceOf(ours, ours));
    double gaussLo = 1.0, gaussHi = 0.0, scaledLo = 1.0, scaledHi = 0.0;
    std::fprintf(out, "axis truth noise (its variance less the real roll's, by");
    for (const auto& [name, variance] : real) {
        const double sd = std::sqrt(std::max(0.0, axisVariance - variance));
        const double gauss = sd > 0.0 ? std::erf(5.0 / (sd * std::sqrt(2.0))) : 1.0;
        const double limit = sd > 0.0 ? 5.0 * oursSd / sd : INFINITY;
        const double scaled =
            ours.empty()
                ? 0.0
                : static_cast<double>(std::count_if(
                      ours.begin(), ours.end(), [&](double e) { return std::fabs(e) <= limit; })) /
                      static_cast<double>(ours.size());
        gaussLo = std::min(gaussLo, gauss);
        gaussHi = std::max(gaussHi, gauss);
        scaledLo = std::min(scaledLo, scaled);
        scaledHi = std::max(scaledHi, scaled);
        std::fprintf(out, " %s: sd %.2f deg", name, sd);
    }
    std::fprintf(out,
                 "); an exact roll estimator scored against this truth: within5 %.3f-%.3f if the "
                 "noise is Gaussian, %.3f-%.3f if it is shaped like our errors (sd %.2f deg)\n",
                 gaussLo, gaussHi, scaledLo, scaledHi, oursSd);
}

int cropSide(const LandmarkFace& face, int minSide)
{
    return std::max(static_cast<int>(std::lround(3.0 * face.eyeMouthDistance())), minSide);
}

}  // namespace

int runRollEval(const RollEvalOptions& o, std::FILE* out, std::FILE* err)
{
    try {
        if (!(o.rotateDegrees >= 0.0 && o.rotateDegrees <= 90.0))
            throw std::runtime_error("--rotate must be in [0, 90] degrees");
        if (o.corners < 3 || o.corners > vision::kMaxRollPoints)
            throw std::runtime_error("--corners must be in [3, " +
                                     std::to_string(vision::kMaxRollPoints) + "]");
        if (!(o.cornerBlurFraction >= 0.f && o.cornerBlurFraction < 0.2f))
            throw std::runtime_error("--corner-blur must be in [0, 0.2)");
        std::vector<LandmarkFace> truth = loadLandmarkFaces(o.truth);
        if (o.maxFaces > 0 && static_cast<int>(truth.size()) > o.maxFaces)
            truth.resize(static_cast<std::size_t>(o.maxFaces));

        std::map<std::string, cv::Mat> images;
        int largest = 0;
        for (const LandmarkFace& f : truth) {
            largest = std::max(largest, cropSide(f, o.minCropSide));
            if (images.count(f.image))
                continue;
            const std::string path = (std::filesystem::path(o.images) / f.image).string();
            if (!std::filesystem::exists(path))
                throw std::runtime_error("image " + path + ": no such file");
            cv::Mat g = cv::imread(path, cv::IMREAD_GRAYSCALE);
            if (g.empty())
                throw std::runtime_error("image " + path + ": cannot decode");
            images.emplace(f.image, std::move(g));
        }
        largest += 2;  // rounding of the side

        const std::string cascadePath = o.cascade.empty() ? kDefaultCascade : o.cascade;
        const vision::HaarCascade cascade = vision::loadHaarCascade(cascadePath);
        vision::CornerDetectorOptions copt;
        copt.maxCorners = o.corners;
        vision::CornerDetector cornerDetector({largest, largest}, copt);

        // The dissertation's own scoring: whole degrees, plain mean, axis through the box centre.
        vision::RollEstimatorOptions plain;
        plain.refineToleranceDegrees = 0.f;
        plain.trimFraction = 0.f;
        plain.capFraction = 0.f;
        plain.maxAxisOffsetFraction = 0.f;

        // The primary method: dense image symmetry, defaults as chosen on the IMM faces.
        vision::RollByImageSymmetryOptions imageOptions;
        imageOptions.patchSize = o.imagePatch;
        imageOptions.boxScale = o.imageBoxScale;
        imageOptions.maxAxisOffsetFraction = o.imageAxisOffset;
        imageOptions.regionHalfWidthFraction = o.imageHalfWidth;
        imageOptions.regionTop = o.imageTop;
        imageOptions.regionBottom = o.imageBottom;
        imageOptions.blurPasses = o.imageBlur;
        imageOptions.coarseStepDegrees = o.imageStep;
        imageOptions.feature = o.imageIntensity ? vision::SymmetryFeature::Intensity
                                                : vision::SymmetryFeature::Gradient;
        imageOptions.gradientSaturation = o.imageSaturation;
        imageOptions.axisWeightSigma = o.imageAxisSigma;
        vision::RollByImageSymmetry imageSymmetry(imageOptions);
        const vision::RollByImageSymmetryOptions& io = imageSymmetry.options();

        ErrorStats image{"image symmetry (primary)", {}};
        ErrorStats symmetry{"corner symmetry (tuned)", {}};
        ErrorStats dissertation{"corner symmetry, dissertation's", {}};
        ErrorStats lineFit{"line-fit baseline", {}};
        ErrorStats upright{"assume upright (0)", {}};
        ErrorStats truthCentre{"diag: corners about truth centre", {}};
        ErrorStats eyeLine{"diag: image symmetry vs eye-line", {}};
        ErrorStats truthNoise{"diag: eye-line truth vs axis truth", {}};
        ErrorStats large{"diag: image symmetry, e-m >= 20 px", {}};
        ErrorStats confident{"diag: image symmetry, conf >= 0.3", {}};
        ErrorStats turned{"diag: image symmetry, |yaw| >= 0.1", {}};
        ErrorStats cascadeRoll{"diag: cascade response", {}};
        CascadeResponseRoll cascadeResponse(cascade);
        UnrotatedRolls unrotated;
        std::vector<double> cornerCounts, centreOffsets, boxPerEyeMouth;
        int missed = 0, tooSmall = 0;

        std::fprintf(out, "roll eval: %zu faces of %s; cascade %s\n", truth.size(), o.truth.c_str(),
                     cascadePath.c_str());
        const std::string resample = o.minCropSide > 0
                                         ? ", crops under " + std::to_string(o.minCropSide) +
                                               " px resampled up to it (same warp)"
                                         : ", native resolution";
        std::fprintf(out,
                     "protocol: square crop 3x eye-mouth distance about the face centre (midpoint "
                     "of eye midpoint and mouth centre), border replicated, rotated about it by "
                     "uniform [-%.0f, %.0f] deg (seed %u)%s\n",
                     o.rotateDegrees, o.rotateDegrees, o.seed, resample.c_str());
        std::fprintf(out,
                     "detector: ours, scale factor 1.1, min neighbours 3, min size crop/4; a face "
                     "counts when a detection holds its eye midpoint and mouth centre (the one "
                     "closest to the crop centre)\n");
        std::fprintf(out,
                     "corners: CornerDetector, at most %d per box, min distance %.3f x box side, "
                     "on the crop smoothed by a Gaussian of sigma %.3f x box side; roll: "
                     "estimateRollBySymmetry with its default options about the box centre\n",
                     o.corners, static_cast<double>(o.cornerDistanceFraction),
                     static_cast<double>(o.cornerBlurFraction));
        std::fprintf(out,
                     "truth roll: orthogonal LS line through eye midpoint, nose, mouth centre, "
                     "from vertical, clockwise on screen positive (RollEstimate's sense)\n");
        std::fprintf(
            out,
            "primary method: image symmetry (RollByImageSymmetry: the box x %.2f warped "
            "upright into a %d px patch per angle, %s mirror asymmetry (saturation "
            "%.1f) over a region +-%.2f wide, axis offset up to %.2f of the patch; "
            "angles [%.0f, %.0f] in %.1f deg steps, best interior minimum, golden section to "
            "%.2f deg; plus %.2f x (1 - row coherence of the vertical derivatives)); the "
            "corner-symmetry rows are the dissertation's method (5.2)\n",
            static_cast<double>(io.boxScale), io.patchSize,
            io.feature == vision::SymmetryFeature::Gradient ? "gradient" : "intensity",
            static_cast<double>(io.gradientSaturation),
            static_cast<double>(io.regionHalfWidthFraction),
            static_cast<double>(io.maxAxisOffsetFraction), static_cast<double>(io.minDegrees),
            static_cast<double>(io.maxDegrees), static_cast<double>(io.coarseStepDegrees),
            static_cast<double>(io.refineToleranceDegrees),
            static_cast<double>(io.rowCoherenceWeight));
        if (o.perFace)
            std::fprintf(out, "%-28s %4s %5s %7s %7s %7s %5s %7s %7s %5s %6s %6s %6s\n", "image",
                         "line", "d_px", "rot", "truth", "image", "conf", "corner", "linefit",
                         "pts", "offset", "yaw", "eye");

        std::mt19937 rng(o.seed);
        std::uniform_real_distribution<double> angle(-o.rotateDegrees, o.rotateDegrees);
        std::vector<vision::Corner> corners(static_cast<std::size_t>(o.corners));
        for (const LandmarkFace& f : truth) {
            const double rotation = angle(rng);  // drawn for every face: same angles per seed
            const Crop crop = makeCrop(images.at(f.image), f, rotation, o.minCropSide);
            const double truthRoll = axisRollDegrees(crop.axis[0], crop.axis[1], crop.axis[2]);
            const int side = crop.gray.cols;
            const vision::ConstImageView view{crop.gray.data, side, side,
                                              static_cast<int>(crop.gray.step),
                                              vision::PixelFormat::Gray8};
            if (side < cascade.windowWidth || side < cascade.windowHeight) {
                ++tooSmall;
                ++missed;
                continue;
            }
            // One detector per crop: its buffers and min size follow the crop (a tool, not the
            // frame loop).
            vision::FaceDetectorOptions dopt;
            dopt.maxFrameSize = {side, side};
            dopt.minSize = {side / 4, side / 4};
            vision::FaceDetector detector(cascade, dopt);
            if (detector.detect(view) < 0)
                throw std::runtime_error(f.image + ": " + detector.lastError());
            const vision::Rect* best = nullptr;
            double bestDistance = 0.0;
            const double mid = 0.5 * (side - 1);
            for (const vision::Rect& b : detector.faces()) {
                const BoxF box = toBoxF(b);
                if (!contains(box, crop.axis[0]) || !contains(box, crop.axis[2]))
                    continue;
                const double dist =
                    std::hypot(b.x + 0.5 * (b.width - 1) - mid, b.y + 0.5 * (b.height - 1) - mid);
                if (best == nullptr || dist < bestDistance) {
                    best = &b;
                    bestDistance = dist;
                }
            }
            if (best == nullptr) {
                ++missed;
                continue;
            }
            const vision::Rect box = *best;
            const vision::Point2f centre{
                static_cast<float>(box.x) + 0.5f * static_cast<float>(box.width - 1),
                static_cast<float>(box.y) + 0.5f * static_cast<float>(box.height - 1)};
            const auto size = static_cast<float>(box.width);

            // Corners at the scale of the facial features (eyes, nostrils, mouth corners) rather
            // than of pixel noise and JPEG/GIF texture: smoothing in proportion to the face.
            cv::Mat smooth = crop.gray;
            if (o.cornerBlurFraction > 0.f)
                cv::GaussianBlur(crop.gray, smooth, cv::Size(0, 0),
                                 static_cast<double>(o.cornerBlurFraction * size));
            const vision::ConstImageView smoothView{
                smooth.data, side, side, static_cast<int>(smooth.step), vision::PixelFormat::Gray8};
            cornerDetector.setMinDistance(size * o.cornerDistanceFraction);
            const int n = cornerDetector.detect(smoothView, box, corners.data(), o.corners);
            std::vector<vision::Point2f> points;
            for (int k = 0; k < n; ++k)
                points.push_back(corners[static_cast<std::size_t>(k)].position);

            // warpUpright's continuous coordinates: the box centre is x + width / 2.
            const vision::Point2f boxCentre{
                static_cast<float>(box.x) + 0.5f * static_cast<float>(box.width),
                static_cast<float>(box.y) + 0.5f * static_cast<float>(box.height)};
            const auto byImage = imageSymmetry.estimate(view, boxCentre, size);
            if (byImage.confidence <= 0.f && imageSymmetry.lastError()[0] != '\0')
                throw std::runtime_error(f.image + ": " + imageSymmetry.lastError());
            const auto ours = vision::estimateRollBySymmetry(points, centre, size);
            const auto theirs = vision::estimateRollBySymmetry(points, centre, size, plain);
            const auto line = vision::estimateRollByLineFit(points);
            const vision::Point2f faceCentre{0.5f * (crop.axis[0].x + crop.axis[2].x),
                                             0.5f * (crop.axis[0].y + crop.axis[2].y)};
            const auto atTruth = vision::estimateRollBySymmetry(points, faceCentre, size);
            const double error = std::fabs(byImage.rollDegrees - truthRoll);
            image.values.push_back(error);
            if (byImage.confidence >= 0.3f)
                confident.values.push_back(error);
            symmetry.values.push_back(std::fabs(ours.rollDegrees - truthRoll));
            dissertation.values.push_back(std::fabs(theirs.rollDegrees - truthRoll));
            lineFit.values.push_back(std::fabs(line.rollDegrees - truthRoll));
            upright.values.push_back(std::fabs(truthRoll));
            truthCentre.values.push_back(std::fabs(atTruth.rollDegrees - truthRoll));
            // The eye line's roll: the angle of left eye -> right eye from horizontal, rotated.
            const double eyeRoll =
                std::atan2(f.rightEye.y - f.leftEye.y, f.rightEye.x - f.leftEye.x) * 180.0 /
                    3.14159265358979323846 +
                rotation;
            eyeLine.values.push_back(std::fabs(byImage.rollDegrees - eyeRoll));
            truthNoise.values.push_back(std::fabs(eyeRoll - truthRoll));
            const double byCascade = cascadeResponse.estimate(view, boxCentre, size);
            cascadeRoll.values.push_back(std::fabs(byCascade - truthRoll));
            if (std::fabs(byImage.rollDegrees - byCascade) <= 10.0) {
                unrotated.axis.push_back(truthRoll - rotation);
                unrotated.eyeLine.push_back(eyeRoll - rotation);
                unrotated.image.push_back(byImage.rollDegrees - rotation);
                unrotated.cascade.push_back(byCascade - rotation);
            }
            if (f.eyeMouthDistance() >= 20.f)
                large.values.push_back(error);
            // Yaw proxy: the nose's sideways offset from the eye-midpoint-mouth line, per
            // eye-mouth distance (turned heads have the nose off their midline).
            const vision::Point2f em = f.eyeMidpoint();
            const double ax = f.mouthCentre.x - em.x, ay = f.mouthCentre.y - em.y;
            const double yaw = ((f.nose.x - em.x) * ay - (f.nose.y - em.y) * ax) /
                               std::max(1e-6, ax * ax + ay * ay);
            if (std::fabs(yaw) >= 0.1)
                turned.values.push_back(error);
            cornerCounts.push_back(n);
            const double offset =
                std::hypot(centre.x - faceCentre.x, centre.y - faceCentre.y) / size;
            centreOffsets.push_back(offset);
            boxPerEyeMouth.push_back(3.0 * size / side);  // the crop is 3 eye-mouth distances
            if (o.perFace)
                std::fprintf(
                    out,
                    "%-28s %4d %5.1f %7.2f %7.2f %7.2f %5.2f %7.2f %7.2f %5d %6.3f %6.3f "
                    "%6.2f\n",
                    f.image.c_str(), f.line, static_cast<double>(f.eyeMouthDistance()), rotation,
                    truthRoll, static_cast<double>(byImage.rollDegrees),
                    static_cast<double>(byImage.confidence), static_cast<double>(ours.rollDegrees),
                    static_cast<double>(line.rollDegrees), n, offset, yaw, eyeRoll - truthRoll);
        }

        std::fprintf(out,
                     "faces: %zu, detected %zu, missed %d (%d crops smaller than the window)\n",
                     truth.size(), image.values.size(), missed, tooSmall);
        std::fprintf(out,
                     "detected boxes: %.1f corners on average, box centre %.3f of the box side "
                     "from the face centre, box side %.2f x eye-mouth distance\n",
                     meanOf(cornerCounts), meanOf(centreOffsets), meanOf(boxPerEyeMouth));
        std::fprintf(out, "%-36s %6s %9s %8s %8s %8s\n", "method", "faces", "mean_deg", "p90_deg",
                     "within1", "within5");
        for (const ErrorStats* e :
             {&image, &symmetry, &dissertation, &lineFit, &upright, &truthCentre, &eyeLine,
              &truthNoise, &large, &confident, &turned, &cascadeRoll})
            std::fprintf(out, "%-36s %6zu %9.2f %8.2f %8.3f %8.3f\n", e->name, e->values.size(),
                         e->mean(), e->percentile(0.9), e->within(1.0), e->within(5.0));
        printTruthNoise(unrotated, out);
        std::fprintf(out, "method: image symmetry (RollByImageSymmetry)\n");
        std::fprintf(out, "roll: faces=%zu mean_err_deg=%.2f within1=%.3f within5=%.3f\n",
                     image.values.size(), image.mean(), image.within(1.0), image.within(5.0));
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(err, "mirror-eval roll: %s\n", e.what());
        return 1;
    }
}

}  // namespace mirror_eval
