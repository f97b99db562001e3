// mirror-eval aam --imm: the fitted yaw on IMM's frontal and turned heads (aam_eval.hpp).
#include "aam_eval_report.hpp"
#include "annotation_files.hpp"
#include "dlib_peer.hpp"
#include "head_texture.hpp"

#include <algorithm>
#include <map>

namespace mirror_eval::aam_report {

namespace {

/// IMM's photograph type from its file name ("04-3m.asf": 3); 0 when not of that form.
int immTypeOf(const fs::path& path)
{
    const std::string name = path.filename().string();
    return name.size() > 4 && name[2] == '-' && name[3] >= '1' && name[3] <= '6' ? name[3] - '0'
                                                                                 : 0;
}

}  // namespace

int runImmEval(const AamEvalOptions& o, std::FILE* out)
{
    if (!fs::is_directory(o.imm))
        throw UsageError("--imm " + o.imm + ": not a folder");
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(o.imm)) {
        const int type = immTypeOf(e.path());
        if (e.path().extension() == ".asf" && (type == 1 || type == 3 || type == 4) &&
            (o.allPersons || headgen::heldOutOfDemoModel(e.path().string())))
            files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty())
        throw UsageError("--imm " + o.imm + ": no IMM .asf files of types 1, 3 and 4");
    DlibPeer dlib(o.predictor, o.upsample);
    auto runner = makeRunner(o, dlib);
    printFitterLine(out, *runner);
    std::fprintf(out,
                 "IMM %s: types 1 (frontal), 3 (turned to the person's right: yaw < 0 expected), "
                 "4 (to the left: yaw > 0); %s; boxes: dlib HOG\n",
                 o.imm.c_str(),
                 o.allPersons ? "ALL persons, PERSON-SPECIFIC: the demo model saw 30 of them"
                              : "the persons the demo model leaves out (04, 08, ... 40)");
    struct TypeScores {
        PeerScores ours, peer;
        std::vector<double> yaw;
        int signRight = 0;
    };
    std::map<int, TypeScores> byType;
    for (const fs::path& asf : files) {
        const int type = immTypeOf(asf);
        TypeScores& t = byType[type];
        const aam::Annotation annotation = aam::loadAnnotation(asf.string());
        const CandidePoints truth = candidePointsOf(aam::immScheme(), annotation.points);
        const std::optional<double> eyes = eyeCornerDistance(truth);
        const cv::Mat grey = readGrey(asf.parent_path() / annotation.hostImage);
        const std::optional<FaceBoxPx> box =
            dlib.detectNear(grey, boundingBoxOf(annotation.points));
        runner->restart();
        if (!box || !eyes) {
            ++t.ours.lost, ++t.peer.lost;
            continue;
        }
        if (const auto fit = runOurs(*runner, grey, *box, t.ours)) {
            t.ours.addNme(frameNme(
                truth, candidePointsOf(runner->mesh().candideNumber, fit->vertices), *eyes));
            if (fit->angles) {
                t.yaw.push_back(fit->angles->yawDeg);
                const double y = fit->angles->yawDeg;
                t.signRight += (type == 3 && y < 0) || (type == 4 && y > 0);
            }
        }
        t.peer.addNme(frameNme(
            truth, candidePointsOf(aam::ibugScheme(), runDlib(dlib, grey, *box, t.peer)), *eyes));
    }
    std::fprintf(out, "%-5s %6s %5s %9s %9s %10s %8s %8s\n", "type", "images", "lost", "yaw_mean",
                 "|yaw|", "sign_right", "nme", "dlib_nme");
    int signRight = 0, turned = 0;
    for (const auto& [type, t] : byType) {
        std::vector<double> magnitude;
        for (double y : t.yaw)
            magnitude.push_back(std::abs(y));
        const bool isTurned = type == 3 || type == 4;
        if (isTurned) {
            signRight += t.signRight;
            turned += static_cast<int>(t.yaw.size());
        }
        std::fprintf(
            out, "%-5d %6zu %5ld %9s %9s %10s %8s %8s\n", type,
            t.ours.nme.values.size() + static_cast<std::size_t>(t.ours.lost), t.ours.lost,
            number(meanOrNan(t.yaw), "%.2f").c_str(), number(meanOrNan(magnitude), "%.2f").c_str(),
            isTurned && !t.yaw.empty()
                ? (std::to_string(t.signRight) + "/" + std::to_string(t.yaw.size())).c_str()
                : "-",
            number(meanOrNan(t.ours.nme.values)).c_str(),
            number(meanOrNan(t.peer.nme.values)).c_str());
    }
    if (runner->placeholder())
        std::fprintf(out,
                     "yaw unavailable: the placeholder has no pose (vision's AAM fit is not "
                     "wired yet)\n");
    const auto yawOf = [&](int type) {
        const auto it = byType.find(type);
        return it == byType.end() ? kNan : meanOrNan(it->second.yaw);
    };
    std::fprintf(out,
                 "aam-imm: images=%zu type1_yaw=%s type3_yaw=%s type4_yaw=%s sign_right=%d/%d\n",
                 files.size(), number(yawOf(1), "%.2f").c_str(), number(yawOf(3), "%.2f").c_str(),
                 number(yawOf(4), "%.2f").c_str(), signRight, turned);
    return 0;
}

}  // namespace mirror_eval::aam_report
