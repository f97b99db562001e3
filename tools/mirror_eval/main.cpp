// mirror-eval: evaluates the vision core on recorded or generated sequences with ground truth.
// One sub-command per tracker: `card` (§2), `detect` and `track` (§3), `roll` (§4); and
// `liveness`, the cues that tell a living face from a photograph (§3); `aam`, the Active
// Appearance Model fit (§5) beside dlib's shape predictor; `people`, who a face is from the fitted
// model's signature (§6).

#include "aam_eval.hpp"
#include "card_eval.hpp"
#include "detect_eval.hpp"
#include "liveness_eval.hpp"
#include "people_eval.hpp"
#include "roll_eval.hpp"
#include "shared_data.hpp"
#include "tool_cli.hpp"
#include "track_eval.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>

int main(int argc, char** argv)
{
    CLI::App app{"mirror-eval: scores the vision core against ground truth"};
    app.require_subcommand(1);
    tool_cli::addVersion(app, "mirror-eval");

    mirror_eval::CardEvalOptions card;
    CLI::App* cardCmd =
        app.add_subcommand("card",
                           "the colour-card tracker on a video or frame folder with a truth CSV "
                           "(frame,x0,y0,x1,y1,x2,y2,x3,y3; empty corners = no card)");
    cardCmd->add_option("--video", card.video, "video file or folder of frames")->required();
    cardCmd->add_option("--truth", card.truth, "truth CSV, one row per frame")->required();
    cardCmd
        ->add_option("--train-fraction", card.trainFraction,
                     "central fraction of frame 0 that trains the colour model")
        ->capture_default_str();
    cardCmd->add_flag("--deinterlace", card.deinterlace,
                      "deinterlace first (the firmware's vision.deinterlace = true)");
    cardCmd->add_option("--per-frame", card.perFrameCsv,
                        "also write the tracker's per-frame corners and errors to this CSV");

    mirror_eval::DetectEvalOptions detect;
    CLI::App* detectCmd =
        app.add_subcommand("detect",
                           "our Viola-Jones detector on a CMU/MIT set (6-point truth) and beside "
                           "cv::CascadeClassifier with the same cascade and parameters");
    detectCmd->add_option("--images", detect.images, "folder of the images")->required();
    detectCmd->add_option("--truth", detect.truth, "landmarks file, one face per line")->required();
    detectCmd->add_option("--cascade", detect.cascade, "OpenCV Haar cascade XML")
        ->capture_default_str();
    detectCmd->add_option("--scale-factor", detect.scaleFactor)->capture_default_str();
    detectCmd->add_option("--min-neighbors", detect.minNeighbors)->capture_default_str();
    detectCmd->add_option("--min-size", detect.minSize, "smallest box side, 0: the window's")
        ->capture_default_str();
    detectCmd->add_option("--max-images", detect.maxImages, "only the first N images (0: all)");
    bool detectQuiet = false;
    detectCmd->add_flag("--summary-only", detectQuiet, "no per-image lines");

    mirror_eval::RollEvalOptions roll;
    CLI::App* rollCmd = app.add_subcommand(
        "roll",
        "initial roll by image symmetry (and by corner symmetry, the dissertation's) on "
        "rotated crops of the CMU/MIT faces");
    rollCmd->add_option("--images", roll.images, "folder of the images")->required();
    rollCmd->add_option("--truth", roll.truth, "landmarks file, one face per line")->required();
    rollCmd->add_option("--rotate", roll.rotateDegrees, "crops rotate uniformly in +-this")
        ->capture_default_str();
    rollCmd->add_option("--seed", roll.seed, "seed of the rotation angles")->capture_default_str();
    rollCmd->add_option("--cascade", roll.cascade,
                        "OpenCV Haar cascade XML (default: "
                        "haarcascade_frontalface_default)");
    rollCmd->add_option("--corners", roll.corners, "most corners per face")->capture_default_str();
    rollCmd
        ->add_option("--corner-distance", roll.cornerDistanceFraction,
                     "min distance between corners as a fraction of the box side")
        ->capture_default_str();
    rollCmd
        ->add_option("--min-crop", roll.minCropSide,
                     "crops smaller than this side (px) are resampled up to it; 0: native")
        ->capture_default_str();
    rollCmd
        ->add_option("--corner-blur", roll.cornerBlurFraction,
                     "Gaussian sigma before corner detection, as a fraction of the box side")
        ->capture_default_str();
    rollCmd->add_option("--image-patch", roll.imagePatch, "image symmetry: patch side (px)")
        ->capture_default_str();
    rollCmd->add_option("--image-box-scale", roll.imageBoxScale, "image symmetry: square / box")
        ->capture_default_str();
    rollCmd
        ->add_option("--image-axis-offset", roll.imageAxisOffset,
                     "image symmetry: largest axis offset / patch side")
        ->capture_default_str();
    rollCmd
        ->add_option("--image-half-width", roll.imageHalfWidth,
                     "image symmetry: compared half-width / patch side")
        ->capture_default_str();
    rollCmd->add_option("--image-top", roll.imageTop, "image symmetry: region top / patch side")
        ->capture_default_str();
    rollCmd
        ->add_option("--image-bottom", roll.imageBottom,
                     "image symmetry: region bottom / patch side")
        ->capture_default_str();
    rollCmd->add_option("--image-blur", roll.imageBlur, "image symmetry: [1 2 1] passes")
        ->capture_default_str();
    rollCmd->add_option("--image-step", roll.imageStep, "image symmetry: coarse angle step (deg)")
        ->capture_default_str();
    rollCmd->add_flag("--image-intensity", roll.imageIntensity,
                      "image symmetry: compare intensities instead of gradients");
    rollCmd
        ->add_option("--image-saturation", roll.imageSaturation,
                     "image symmetry: gradient saturation (grey levels; 0: linear)")
        ->capture_default_str();
    rollCmd
        ->add_option("--image-axis-sigma", roll.imageAxisSigma,
                     "image symmetry: pair weight sigma / patch side (0: uniform)")
        ->capture_default_str();
    rollCmd->add_option("--max-faces", roll.maxFaces, "only the first N faces (0: all)");
    rollCmd->add_flag("--per-face", roll.perFace, "one line per face");

    mirror_eval::TrackEvalOptions track;
    CLI::App* trackCmd = app.add_subcommand(
        "track",
        "the face pipeline (motion + detection + tracking) over a frame folder, the "
        "configurations of the dissertation's Table 6");
    trackCmd->add_option("--frames", track.frames, "folder of frames, in file-name order")
        ->required();
    trackCmd
        ->add_option("--truth", track.truth,
                     "folder of per-frame truth: FGNet .pts or facegen .txt, by frame stem")
        ->required();
    trackCmd
        ->add_option("--config", track.config, "detector | motion | translation | similarity | all")
        ->capture_default_str();
    trackCmd->add_option("--cascade", track.cascade,
                         "OpenCV Haar cascade XML (default: "
                         "haarcascade_frontalface_default)");
    trackCmd->add_option("--downscale", track.downscale, "working resolution = frame / this")
        ->capture_default_str();
    trackCmd->add_option("--min-size", track.minSize, "detector min face side, working pixels")
        ->capture_default_str();
    trackCmd->add_option("--min-iou", track.minIou, "IoU a match needs")->capture_default_str();
    trackCmd
        ->add_option("--budget", track.budget,
                     "detector windows per frame, 0: whole scans (the mirror ships 5000)")
        ->capture_default_str();
    trackCmd
        ->add_option("--start", track.start,
                     "start at frame N (in file-name order) cold, as at power-on, and score "
                     "only frames from N on")
        ->capture_default_str();
    trackCmd->add_option("--max-frames", track.maxFrames,
                         "only the first N frames from --start (0: all)");
    trackCmd->add_flag("--per-frame", track.perFrame, "print every frame's faces and truth");
    trackCmd->add_flag("--no-sway", track.noSway,
                       "faces must move to be shown, as before a calm face's sway counted "
                       "(FaceTrackerOptions::livenessBySway = false), for comparison");

    mirror_eval::LivenessEvalOptions liveness;
    CLI::App* livenessCmd = app.add_subcommand(
        "liveness",
        "cues that tell a living face from a photograph, measured over each truth face's "
        "first frames (living: FGNet; moving and static: facegen)");
    livenessCmd->add_option("--frames", liveness.frames, "folder of frames, in file-name order")
        ->required();
    livenessCmd
        ->add_option("--truth", liveness.truth,
                     "folder of per-frame truth: FGNet .pts or facegen .txt, by frame stem")
        ->required();
    livenessCmd->add_option("--downscale", liveness.downscale, "working resolution = frame / this")
        ->capture_default_str();
    livenessCmd->add_option("--every", liveness.every, "a window starts every N frames")
        ->capture_default_str();
    livenessCmd->add_option("--max-frames", liveness.maxFrames, "only the first N frames (0: all)");
    livenessCmd->add_flag("--per-window", liveness.perWindow, "one line per window and step count");

    mirror_eval::AamEvalOptions aam;
    CLI::App* aamCmd = app.add_subcommand(
        "aam",
        "the AAM fit (§5) on an annotated sequence, on headgen's synthetic heads or on IMM's "
        "turned heads, beside dlib's 68-point shape predictor given the same HOG boxes");
    aamCmd->add_option("--frames", aam.frames, "folder of frames, in file-name order");
    aamCmd->add_option("--truth", aam.truth, "folder of per-frame annotations (.pts / .asf)");
    aamCmd->add_option("--scheme", aam.scheme, "the truth's scheme: fgnet, ibug or imm")
        ->capture_default_str();
    aamCmd->add_option("--synthetic", aam.synthetic, "a headgen output folder");
    aamCmd->add_option("--imm", aam.imm, "the IMM face database folder (types 1, 3, 4)");
    aamCmd->add_flag("--all-persons", aam.allPersons,
                     "--imm: every person, also those the demo model was built from "
                     "(person-specific)");
    aamCmd
        ->add_option("--fitter", aam.fitter,
                     "our side: aam (vision's fit as the firmware runs it; needs --model) or "
                     "baseline (the mean shape placed by the box)")
        ->capture_default_str();
    aamCmd->add_option("--model", aam.model, "the .aam model file a real fit loads");
    aam.dataDir = tool_data::defaultDir();
    aamCmd->add_option("--data", aam.dataDir, "the shared data folder (CANDIDE-3, IMM)")
        ->capture_default_str();
    aamCmd->add_option("--predictor", aam.predictor, "dlib's 68-point shape predictor")
        ->capture_default_str();
    aamCmd->add_option("--upsample", aam.upsample, "HOG detector: pyramid_up passes (0-2)")
        ->capture_default_str();
    aamCmd->add_option("--start", aam.start, "first frame (index in file-name order)")
        ->capture_default_str();
    aamCmd->add_option("--max-frames", aam.maxFrames, "only the first N frames (0: all)");
    aamCmd->add_flag("--per-frame", aam.perFrame, "one line per frame");
    aamCmd->add_option("--boxes", aam.boxes,
                       "--frames: a file keeping the HOG boxes between runs (read, and written "
                       "with the frames it lacked)");

    mirror_eval::PeopleEvalOptions people;
    CLI::App* peopleCmd = app.add_subcommand(
        "people",
        "recognition from the fitted AAM's signature (§6): IMM's 40 persons enrolled from one "
        "or two photographs and probed with the others, FGNet's franck through his sequence; "
        "Viola-Jones boxes, the fit as the firmware runs it");
    peopleCmd->add_option("--model", people.model, "the .aam model file")->required();
    people.dataDir = tool_data::defaultDir();
    peopleCmd->add_option("--data", people.dataDir, "the shared data folder")
        ->capture_default_str();
    peopleCmd->add_option("--imm", people.imm, "the IMM folder (default DATA/imm_face_db; none)");
    peopleCmd->add_option("--frames", people.frames,
                          "franck's frames (default DATA/fgnet_talking_face/images; none)");
    peopleCmd->add_option("--truth", people.truth,
                          "per-frame .pts for --frames: the face holding their centre is franck "
                          "(default with the default frames: DATA/fgnet_talking_face/points)");
    peopleCmd->add_option("--stranger", people.stranger,
                          "a facegen folder whose moving face must not be taken for franck");
    peopleCmd->add_option("--cascade", people.cascade, "the detector's Haar cascade")
        ->capture_default_str();
    peopleCmd->add_option("--enrol", people.enrol, "IMM types a person is enrolled from: 1 or 1,2")
        ->capture_default_str();
    peopleCmd->add_option("--persons", people.persons, "IMM: only persons 1..N")
        ->capture_default_str();
    peopleCmd->add_option("--enrol-frames", people.enrolFrames, "FGNet: franck's enrolment frames")
        ->capture_default_str();
    peopleCmd->add_option("--window", people.window, "FGNet: frames per recognition track")
        ->capture_default_str();
    peopleCmd->add_option("--max-frames", people.maxFrames, "FGNet: only the first N (0: all)");
    peopleCmd->add_option("--max-fits", people.maxFits, "fits of a still image at most")
        ->capture_default_str();
    peopleCmd->add_option("--accept", people.acceptScore, "the gallery's acceptScore (measuring)");
    peopleCmd->add_option("--shape-weight", people.shapeWeight, "the gallery's shapeWeight");
    peopleCmd->add_option("--appearance-weight", people.appearanceWeight,
                          "the gallery's appearanceWeight");
    peopleCmd->add_option("--dump", people.dump, "write every signature to this CSV");
    peopleCmd->add_option("--texture-weight", people.textureWeight, "the gallery's textureWeight");
    peopleCmd->add_option("--texture-spread", people.textureSpread, "the gallery's textureSpread");
    peopleCmd->add_option("--signature-residual", people.signatureResidual,
                          "fits rejected only by a residual up to this still make signatures");
    peopleCmd->add_option("--texture-grid", people.textureGrid,
                          "the texture descriptor's cells per side (0: none)");
    peopleCmd->add_flag("--nearest", people.nearest,
                        "the appearance parameters from the nearest pixel (the fit's sampling)");
    peopleCmd->add_flag("--per-image", people.perImage, "say why a photograph has no signature");

    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;
    if (aamCmd->parsed())
        return mirror_eval::runAamEval(aam, stdout, stderr);
    if (peopleCmd->parsed())
        return mirror_eval::runPeopleEval(people, stdout, stderr);
    if (cardCmd->parsed())
        return mirror_eval::runCardEval(card, stdout, stderr);
    if (detectCmd->parsed()) {
        detect.perImage = !detectQuiet;
        return mirror_eval::runDetectEval(detect, stdout, stderr);
    }
    if (rollCmd->parsed())
        return mirror_eval::runRollEval(roll, stdout, stderr);
    if (trackCmd->parsed())
        return mirror_eval::runTrackEval(track, stdout, stderr);
    if (livenessCmd->parsed())
        return mirror_eval::runLivenessEval(liveness, stdout, stderr);
    return 2;
}
