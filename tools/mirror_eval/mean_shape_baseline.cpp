// The mean shape baseline (mean_shape_baseline.hpp): a placeholder, labelled as one wherever it
// is printed.
#include "mean_shape_baseline.hpp"

#include "aam_fit_runner.hpp"
#include "annotation_files.hpp"
#include "annotation_schemes.hpp"
#include "candide_fit.hpp"
#include "head_texture.hpp"
#include "training_image.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace mirror_eval {

namespace fs = std::filesystem;

MeanShapeBaseline::MeanShapeBaseline(const std::string& dataDir, DlibPeer& boxes)
{
    const fs::path data(dataDir);
    mesh_ = vision::reduceCandideForTracking(
        aam::loadWfm((data / "candide3" / "candide3.wfm").string()));
    offsets_.assign(mesh_.vertices.size(), Eigen::Vector2d::Zero());
    std::vector<std::string> photos;
    for (const auto& e : fs::directory_iterator(data / "imm_face_db")) {
        const std::string name = e.path().filename().string();
        if (e.path().extension() == ".asf" && name.size() > 3 && name.substr(2, 2) == "-1" &&
            !headgen::heldOutOfDemoModel(name))
            photos.push_back(e.path().string());
    }
    std::sort(photos.begin(), photos.end());
    for (const std::string& asf : photos) {
        const aam::Annotation annotation = aam::loadAnnotation(asf);
        const cv::Mat grey = aam::loadGreyImage(aam::annotatedImagePath(asf, annotation));
        const std::optional<FaceBoxPx> box =
            boxes.detectNear(grey, boundingBoxOf(annotation.points));
        if (!box)
            continue;
        const aam::CandideFit fit =
            aam::fitCandide(mesh_, aam::markedPoints(aam::immScheme(), annotation, mesh_));
        const auto vertices = aam::projectedVertices(mesh_, fit);
        for (std::size_t v = 0; v < vertices.size(); ++v)
            offsets_[v] += (vertices[v] - box->centre()) / box->width();
        ++photos_;
    }
    if (photos_ == 0)
        throw std::runtime_error((data / "imm_face_db").string() +
                                 ": the detector found no face on the calibration photographs");
    for (auto& o : offsets_)
        o /= photos_;
}

std::string MeanShapeBaseline::label() const
{
    return "mean shape baseline (PLACEHOLDER, not a fit: the mean frontal shape placed by the box)";
}

HeadFit MeanShapeBaseline::fit(const cv::Mat&, const FaceBoxPx& box)
{
    HeadFit f;
    f.held = true;
    for (const Eigen::Vector2d& o : offsets_)
        f.vertices.push_back(box.centre() + box.width() * o);
    return f;
}

std::unique_ptr<HeadFitRunner> makeHeadFitRunner(const HeadFitRunnerOptions& options,
                                                 DlibPeer& boxes)
{
    if (options.fitter == "baseline")
        return std::make_unique<MeanShapeBaseline>(options.dataDir, boxes);
    if (options.fitter == "aam") {
        if (options.model.empty())
            throw std::invalid_argument("--fitter aam needs --model FILE");
        return std::make_unique<AamFitRunner>(options.model, options.dataDir, boxes);
    }
    throw std::invalid_argument("--fitter " + options.fitter + ": unknown (baseline or aam)");
}

}  // namespace mirror_eval
