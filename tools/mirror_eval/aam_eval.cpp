// mirror-eval aam (aam_eval.hpp). Why the choices:
//  - Both peers get dlib's HOG box, the one dlib's predictor was trained on: the comparison is of
//    the fit, not of the detector. A frame where HOG finds no box on the truth face is lost for
//    both (counted apart: the `no HOG box` line).
//  - Everything is compared on CANDIDE vertices through tools/aam's scheme tables, so ours and
//    dlib's are scored on the same truth points (dlib through the iBUG table: the points that
//    table lacks, FGNet's lower brow contour, count for ours only, in `nme_all`).
//  - On FGNet the dlib figure is also given on the FGNet-iBUG pairs alone (no CANDIDE between),
//    the protocol of the dissertation-era comparison the targets quote.
#include "aam_eval.hpp"

#include "aam_eval_report.hpp"
#include "annotation_files.hpp"
#include "box_cache.hpp"

namespace mirror_eval {

namespace {

using namespace aam_report;

void checkArguments(const AamEvalOptions& o)
{
    const int inputs =
        (!o.frames.empty() || !o.truth.empty()) + !o.synthetic.empty() + !o.imm.empty();
    if (inputs != 1)
        throw UsageError("give one of --frames DIR --truth DIR, --synthetic DIR or --imm DIR");
    if (o.frames.empty() != o.truth.empty())
        throw UsageError("--frames and --truth go together");
    if (o.start < 0)
        throw UsageError("--start must be >= 0");
    if (o.maxFrames < 0)
        throw UsageError("--max-frames must be >= 0");
    if (o.upsample < 0 || o.upsample > 2)
        throw UsageError("--upsample must be 0, 1 or 2");
    try {
        aam::schemeNamed(o.scheme);
    } catch (const std::exception& e) {
        throw UsageError(e.what());
    }
}

/// The truth file of a frame: <stem>.pts or <stem>.asf in `dir`.
std::string truthFileOf(const std::string& dir, const fs::path& frame)
{
    for (const char* ext : {".pts", ".asf"}) {
        const fs::path p = fs::path(dir) / (frame.stem().string() + ext);
        if (fs::exists(p))
            return p.string();
    }
    throw std::runtime_error("truth " + dir + ": no " + frame.stem().string() + ".pts or .asf");
}

int runAnnotated(const AamEvalOptions& o, std::FILE* out)
{
    const aam::AnnotationScheme& scheme = aam::schemeNamed(o.scheme);
    const std::vector<fs::path> frames = slice(framesIn(o.frames), o);
    if (!fs::is_directory(o.truth))
        throw UsageError("--truth " + o.truth + ": not a folder");
    DlibPeer dlib(o.predictor, o.upsample);
    BoxCache boxes(o.boxes);
    auto runner = makeRunner(o, dlib);
    printFitterLine(out, *runner);
    std::fprintf(out,
                 "frames %s (%zu from %d), truth %s (scheme %s); boxes: dlib HOG (upsample %d); "
                 "NME over the truth's outer eye corners (CANDIDE 20-53); inner = eyes, nose, "
                 "lips; jaw_corr: jaw drop (dlib: its mouth opening) against the truth's mouth "
                 "opening (CANDIDE 87-40)\n",
                 o.frames.c_str(), frames.size(), o.start, o.truth.c_str(), o.scheme.c_str(),
                 o.upsample);

    PeerScores ours{oursName(*runner)}, peer{"dlib shape predictor 68"};
    std::vector<PairNme> pairs;
    long noBox = 0;
    int oursPoints = 0, dlibPoints = 0;
    std::vector<double> detectMs;
    runner->restart();
    for (const fs::path& frame : frames) {
        const cv::Mat grey = readGrey(frame);
        const std::vector<Eigen::Vector2d> annotation =
            aam::loadAnnotation(truthFileOf(o.truth, frame)).points;
        const CandidePoints truth = candidePointsOf(scheme, annotation);
        const std::optional<double> eyes = eyeCornerDistance(truth);
        std::optional<FaceBoxPx> box;
        if (const auto kept = boxes.find(frame.stem().string())) {
            box = *kept;
        } else {
            const auto t0 = Clock::now();
            box = dlib.detectNear(grey, boundingBoxOf(annotation));
            detectMs.push_back(msSince(t0));
            boxes.put(frame.stem().string(), box);
        }
        if (!box || !eyes) {
            ++noBox, ++ours.lost, ++peer.lost;
            runner->restart();
            continue;
        }
        const std::optional<double> opening = mouthOpening(truth, *eyes);
        if (const auto fit = runOurs(*runner, grey, *box, ours)) {
            const auto f = frameNme(
                truth, candidePointsOf(runner->mesh().candideNumber, fit->vertices), *eyes);
            ours.addNme(f);
            oursPoints = f ? f->allPoints : oursPoints;
            if (fit->animation && opening) {
                ours.jaw.push_back((*fit->animation)[0]);
                ours.jawTruth.push_back(*opening);
            }
            if (o.perFrame && f)
                std::fprintf(out, "frame %s ours nme=%.4f nme_all=%.4f iterations=%d\n",
                             frame.stem().c_str(), f->inner, f->all, fit->iterations);
        }
        const std::vector<Eigen::Vector2d> landmarks = runDlib(dlib, grey, *box, peer);
        const CandidePoints dlibPoints68 = candidePointsOf(aam::ibugScheme(), landmarks);
        const auto d = frameNme(truth, dlibPoints68, *eyes);
        peer.addNme(d);
        dlibPoints = d ? d->allPoints : dlibPoints;
        if (const auto theirs = mouthOpening(dlibPoints68, *eyes); theirs && opening) {
            peer.jaw.push_back(*theirs);
            peer.jawTruth.push_back(*opening);
        }
        if (scheme.name == "fgnet")
            pairs.push_back(fgnetIbugNme(annotation, landmarks));
    }
    boxes.save();
    printHeader(out);
    printRow(out, ours, oursPoints);
    printRow(out, peer, dlibPoints);
    if (!pairs.empty()) {
        const PairNme p = meanPairNme(pairs);
        std::fprintf(out,
                     "dlib on the FGNet-iBUG pairs alone: inner (eyes, nose, lips) %d points "
                     "%.4f, with the chin %d: %.4f; with the pupils and the mouth centre (means "
                     "of iBUG contours) %d: %.4f, and the chin %d: %.4f; all %d pairs %.4f\n",
                     p.innerPoints, p.inner, p.innerAndChinPoints, p.innerAndChin,
                     p.withCentresPoints, p.withCentres, p.withCentresAndChinPoints,
                     p.withCentresAndChin, p.allPoints, p.all);
    }
    std::fprintf(out,
                 "no HOG box on the truth face: %ld of %zu frames; HOG %.1f ms per frame (%zu "
                 "frames detected, the others' boxes from --boxes)\n",
                 noBox, frames.size(), detectMs.empty() ? 0.0 : meanOf(detectMs),
                 detectMs.size());
    if (runner->placeholder())
        std::fprintf(out, "* placeholder: not the AAM fit\n");
    std::fprintf(out,
                 "aam: frames=%zu nme=%s nme_p90=%s nme_all=%s dlib_nme=%s jaw_corr=%s iters=%s "
                 "ms_per_frame=%s lost=%ld\n",
                 frames.size(), number(meanOrNan(ours.nme.values)).c_str(),
                 number(p90OrNan(ours.nme)).c_str(), number(meanOrNan(ours.nmeAll.values)).c_str(),
                 number(meanOrNan(peer.nme.values)).c_str(),
                 number(ours.jawCorrelation(), "%.3f").c_str(),
                 number(meanOrNan(ours.iterations), "%.2f").c_str(),
                 number(meanOrNan(ours.ms), "%.3f").c_str(), ours.lost);
    return 0;
}

}  // namespace

int runAamEval(const AamEvalOptions& o, std::FILE* out, std::FILE* err)
{
    try {
        checkArguments(o);
        if (!o.synthetic.empty())
            return runSyntheticEval(o, out);
        if (!o.imm.empty())
            return runImmEval(o, out);
        return runAnnotated(o, out);
    } catch (const UsageError& e) {
        std::fprintf(err, "mirror-eval aam: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(err, "mirror-eval aam: %s\n", e.what());
        return 1;
    }
}

}  // namespace mirror_eval
