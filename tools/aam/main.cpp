// aam-build: the offline Active Appearance Model builder (§5). So far: `mesh` reads CANDIDE-3 and
// reports the dissertation's cut of it; `draw` pictures an annotated image with its points
// numbered; `fit` fits the cut CANDIDE to annotated images (5.3.1, eq. 44) and pictures a fit;
// `shapes` synthesizes the training shapes from the fits, aligns them (weighted Procrustes) and
// counts the shape modes; `model` builds the whole model (shape and appearance), writes its file
// and evaluates it on held-out persons.
#include "annotation_drawing.hpp"
#include "annotation_files.hpp"
#include "annotation_schemes.hpp"
#include "appearance_warp.hpp"
#include "candide_fit.hpp"
#include "model_building.hpp"
#include "model_evaluation.hpp"
#include "shape_alignment.hpp"
#include "shape_modes.hpp"
#include "shape_synthesis.hpp"
#include "shared_data.hpp"
#include "tool_cli.hpp"
#include "training_image.hpp"
#include "vision/aam_model.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

namespace {

int describeMesh(const std::string& wfm)
{
    const vision::CandideMesh full = aam::loadWfm(wfm);
    const vision::CandideMesh face = vision::reduceCandideForTracking(full);
    std::printf("candide: vertices=%zu triangles=%zu animation_units=%zu shape_units=%zu\n",
                full.vertices.size(), full.triangles.size(), full.animationUnits.size(),
                full.shapeUnits.size());
    std::printf("tracked: vertices=%zu triangles=%zu animation_units=%zu shape_units=%zu\n",
                face.vertices.size(), face.triangles.size(), face.animationUnits.size(),
                face.shapeUnits.size());
    return 0;
}

/// Each point numbered; with a scheme, "point:vertex" where the table maps it to a CANDIDE vertex.
std::vector<std::string> pointLabels(const std::string& scheme, std::size_t count)
{
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < count; ++i)
        labels.push_back(std::to_string(i));
    if (scheme.empty())
        return labels;
    for (const aam::SchemeRow& row : aam::schemeNamed(scheme).rows) {
        for (int k = 0; k < row.at.count(); ++k) {
            const auto p = static_cast<std::size_t>(row.at.points[static_cast<std::size_t>(k)]);
            if (p < count)
                labels[p] += ":" + std::to_string(row.candideVertex);
        }
    }
    return labels;
}

int drawPoints(const std::string& points, const std::string& image, const std::string& scheme,
               const std::string& out)
{
    cv::Mat picture = cv::imread(image, cv::IMREAD_COLOR);
    if (picture.empty())
        throw std::runtime_error(image + ": cannot read the image");
    std::vector<Eigen::Vector2d> marked = aam::loadAnnotation(points).points;
    picture = aam::closeUp(picture, {&marked});
    aam::drawNumberedPoints(picture, marked, pointLabels(scheme, marked.size()));
    if (!cv::imwrite(out, picture))
        throw std::runtime_error(out + ": cannot write the picture");
    return 0;
}

struct FitRequest {
    std::string wfm, scheme;
    std::vector<std::string> points;
    std::string image, out;
    bool perPoint = false;
};

void drawFit(const FitRequest& r, const vision::CandideMesh& face,
             const std::vector<aam::MarkedPoint>& marked, const aam::CandideFit& fit)
{
    cv::Mat picture = cv::imread(r.image, cv::IMREAD_COLOR);
    if (picture.empty())
        throw std::runtime_error(r.image + ": cannot read the image");
    std::vector<Eigen::Vector2d> projected = aam::projectedVertices(face, fit);
    std::vector<Eigen::Vector2d> at;
    std::vector<std::string> labels;
    for (const aam::MarkedPoint& m : marked) {
        at.push_back(m.image);
        labels.push_back(std::to_string(face.candideNumber[static_cast<std::size_t>(m.vertex)]));
    }
    picture = aam::closeUp(picture, {&projected, &at});
    aam::drawMesh(picture, face, projected);
    aam::drawNumberedPoints(picture, at, labels);
    if (!cv::imwrite(r.out, picture))
        throw std::runtime_error(r.out + ": cannot write the picture");
}

void printUnits(const vision::CandideMesh& face, const aam::CandideFit& fit)
{
    for (std::size_t j = 0; j < fit.sigma.size(); ++j)
        std::printf("  sigma %-30s %+.3f\n", face.shapeUnits[j].name.c_str(), fit.sigma[j]);
    for (std::size_t j = 0; j < fit.tau.size(); ++j)
        std::printf("  tau   %-30s %+.3f\n", face.animationUnits[j].name.c_str(), fit.tau[j]);
}

/// Fits every file; one line each, the units of a single file, the mean residual per vertex.
int fitFiles(const FitRequest& r)
{
    const aam::AnnotationScheme& scheme =
        aam::schemeNamed(r.scheme);  // a bad name before any reading
    const vision::CandideMesh face = vision::reduceCandideForTracking(aam::loadWfm(r.wfm));
    std::map<int, std::pair<double, int>> perVertex;  // CANDIDE number: residual sum, count
    double rmsSum = 0;
    for (const std::string& path : r.points) {
        const auto marked = aam::markedPoints(scheme, aam::loadAnnotation(path), face);
        const aam::CandideFit fit = aam::fitCandide(face, marked);
        std::printf("fit %s: points=%zu scale=%.2f roll_deg=%.2f rms_px=%.2f max_px=%.2f\n",
                    path.c_str(), marked.size(), fit.scale(), fit.rollRadians() * 57.29577951308232,
                    fit.rmsResidualPx, fit.maxResidualPx);
        rmsSum += fit.rmsResidualPx;
        const auto projected = aam::projectedVertices(face, fit);
        for (const aam::MarkedPoint& m : marked) {
            auto& [sum, count] = perVertex[face.candideNumber[static_cast<std::size_t>(m.vertex)]];
            sum += (projected[static_cast<std::size_t>(m.vertex)] - m.image).norm();
            ++count;
        }
        if (r.points.size() == 1)
            printUnits(face, fit);
        if (!r.out.empty() && path == r.points.front())
            drawFit(r, face, marked, fit);
    }
    if (r.perPoint) {
        for (const auto& [vertex, sc] : perVertex)
            std::printf("  vertex %3d: mean residual %.2f px\n", vertex, sc.first / sc.second);
    }
    std::printf("fit: files=%zu mean_rms_px=%.2f\n", r.points.size(),
                rmsSum / static_cast<double>(r.points.size()));
    return 0;
}

/// The mean shape, scaled into a square picture, its triangles drawn.
void drawMeanShape(const vision::CandideMesh& face, aam::Shape2d mean, const std::string& out)
{
    Eigen::Vector2d low = mean[0], high = mean[0];
    for (const auto& p : mean) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    const double scale = 700.0 / (high - low).maxCoeff();
    for (auto& p : mean)
        p = (p - low) * scale + Eigen::Vector2d(50, 50);
    cv::Mat picture(800, 800, CV_8UC3, cv::Scalar(255, 255, 255));
    aam::drawMesh(picture, face, mean);
    if (!cv::imwrite(out, picture))
        throw std::runtime_error(out + ": cannot write the picture");
}

/// Every file fitted, its shapes synthesized, all aligned; a summary line.
int alignTrainingShapes(const FitRequest& r)
{
    const aam::AnnotationScheme& scheme = aam::schemeNamed(r.scheme);
    const vision::CandideMesh face = vision::reduceCandideForTracking(aam::loadWfm(r.wfm));
    std::vector<aam::CandideFit> fits;
    for (const std::string& path : r.points)
        fits.push_back(
            aam::fitCandide(face, aam::markedPoints(scheme, aam::loadAnnotation(path), face)));
    const aam::AlignedShapes aligned = aam::alignedTrainingShapes(face, fits, {});
    const aam::ShapeModes model = aam::shapeModes(aligned);
    std::printf(
        "shapes: images=%zu shapes=%zu vertices=%zu iterations=%d weight_min=%.3g weight_max=%.3g "
        "modes=%ld (98%% of the variance)\n",
        r.points.size(), aligned.shapes.size(), face.vertices.size(), aligned.iterations,
        aligned.weights.minCoeff(), aligned.weights.maxCoeff(),
        static_cast<long>(model.modes.cols()));
    if (!r.out.empty())
        drawMeanShape(face, aligned.mean, r.out);
    return 0;
}

struct ModelRequest {
    std::string wfm, scheme, out, picture;
    std::vector<std::string> points, evaluate;
    bool personSpecific = false;
    aam::ModelOptions options;
};

std::vector<aam::FittedImage> fittedImages(const vision::CandideMesh& face,
                                           const aam::AnnotationScheme& scheme,
                                           const std::vector<std::string>& paths)
{
    std::vector<aam::FittedImage> images;
    for (const std::string& path : paths)
        images.push_back(aam::fitAnnotatedImage(face, scheme, path));
    return images;
}

/// The mean appearance and the first modes side by side, each stretched to 0-255, 4x enlarged.
void drawAppearance(const aam::BuiltModel& built, const std::string& out)
{
    std::vector<cv::Mat> tiles{aam::frameImage(built.frame, built.appearance.mean)};
    for (Eigen::Index k = 0; k < std::min<Eigen::Index>(3, built.appearance.modes.cols()); ++k) {
        tiles.push_back(aam::frameImage(built.frame, built.appearance.modes.col(k)));
    }
    for (cv::Mat& t : tiles) {
        cv::normalize(t, t, 0, 255, cv::NORM_MINMAX);
        t.convertTo(t, CV_8U);
        cv::resize(t, t, {}, 4, 4, cv::INTER_NEAREST);
    }
    cv::Mat row;
    cv::hconcat(tiles, row);
    if (!cv::imwrite(out, row))
        throw std::runtime_error(out + ": cannot write the picture");
}

void writeModelFile(const aam::BuiltModel& built, const std::string& out)
{
    const std::string bytes = vision::encodeAamModel(aam::modelForFile(built));
    std::ofstream file(out, std::ios::binary | std::ios::trunc);
    if (!(file << bytes) || !file.flush())
        throw std::runtime_error(out + ": cannot write the model file");
    file.close();
    // Read back as the runtime will: what was written is what it reads.
    const vision::AamModelFile back = vision::loadAamModel(out);
    if (!back.ok)
        throw std::runtime_error(back.problem);
    std::printf("model file %s: bytes=%zu version=%u\n", out.c_str(), bytes.size(),
                vision::kAamModelVersion);
}

void printEvaluation(const std::vector<aam::HeldOutResult>& results, bool personSpecific)
{
    const char* label = personSpecific ? "person-specific" : "held-out";
    aam::HeldOutResult sum;
    for (const aam::HeldOutResult& r : results) {
        std::printf(
            "%s %s: shape_rms_px=%.2f (mean only %.2f) appearance_rms=%.2f (mean only %.2f) "
            "appearance_rms_at_%d=%.2f resolution_loss=%.2f\n",
            label, r.annotationPath.c_str(), r.shapeRmsPx, r.shapeMeanOnlyRmsPx, r.appearanceRms,
            r.appearanceMeanOnlyRms, aam::kReferenceResolution, r.appearanceRmsAtReference,
            r.resolutionLoss);
        sum.shapeRmsPx += r.shapeRmsPx / static_cast<double>(results.size());
        sum.appearanceRms += r.appearanceRms / static_cast<double>(results.size());
        sum.appearanceMeanOnlyRms += r.appearanceMeanOnlyRms / static_cast<double>(results.size());
        sum.appearanceRmsAtReference +=
            r.appearanceRmsAtReference / static_cast<double>(results.size());
        sum.resolutionLoss += r.resolutionLoss / static_cast<double>(results.size());
    }
    std::printf(
        "evaluation (%s): images=%zu shape_rms_px=%.2f appearance_rms=%.2f (mean only %.2f) "
        "appearance_rms_at_%d=%.2f resolution_loss=%.2f\n",
        label, results.size(), sum.shapeRmsPx, sum.appearanceRms, sum.appearanceMeanOnlyRms,
        aam::kReferenceResolution, sum.appearanceRmsAtReference, sum.resolutionLoss);
}

/// Fits, builds, writes, evaluates: one line each (docs/aam-model-format.md, tools/aam/README.md).
int buildModelFile(const ModelRequest& r)
{
    const aam::AnnotationScheme& scheme = aam::schemeNamed(r.scheme);
    if (!r.personSpecific) {  // before any work, so a wrong split writes no model
        std::vector<std::string> persons;
        for (const std::string& path : r.points)
            persons.push_back(aam::personOf(path));
        aam::refuseSeenPersons(persons, r.evaluate);
    }
    const vision::CandideMesh face = vision::reduceCandideForTracking(aam::loadWfm(r.wfm));
    const auto start = std::chrono::steady_clock::now();
    const aam::BuiltModel built =
        aam::buildModel(face, fittedImages(face, scheme, r.points), r.options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf(
        "model: images=%zu persons=%zu shape_modes=%ld frame=%dx%d pixels=%zu appearance_modes=%ld "
        "(%.0f%% of the variance) mean_iterations=%d seconds=%.2f\n",
        r.points.size(), built.persons.size(), static_cast<long>(built.shape.modes.cols()),
        built.frame.width, built.frame.height, built.frame.pixels.size(),
        static_cast<long>(built.appearance.modes.cols()), 100 * r.options.appearanceVariance,
        built.appearance.iterations, seconds);
    if (!r.out.empty())
        writeModelFile(built, r.out);
    if (!r.picture.empty())
        drawAppearance(built, r.picture);
    if (!r.evaluate.empty())
        printEvaluation(
            aam::evaluateHeldOut(built, fittedImages(face, scheme, r.evaluate), r.personSpecific),
            r.personSpecific);
    return 0;
}

/// Reads a model file as the runtime will; one line of counts, or the problem.
int inspectModelFile(const std::string& path)
{
    const vision::AamModelFile f = vision::loadAamModel(path);
    if (!f.ok)
        throw std::runtime_error(f.problem);
    const vision::AamModel& m = f.model;
    std::printf(
        "model %s: version=%u vertices=%zu triangles=%zu animation_units=%zu shape_units=%zu "
        "shape_modes=%zu "
        "frame=%dx%d pixels=%zu appearance_modes=%zu\n",
        path.c_str(), vision::kAamModelVersion, m.mesh.vertices.size(), m.mesh.triangles.size(),
        m.mesh.animationUnits.size(), m.mesh.shapeUnits.size(), m.shapeModeCount(), m.frameWidth,
        m.frameHeight, m.pixels.size(), m.appearanceModeCount());
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"aam-build: the offline Active Appearance Model builder"};
    app.require_subcommand(1);
    tool_cli::addVersion(app, "aam-build");
    std::string wfm = tool_data::defaultDir() + "/candide3/candide3.wfm";
    auto* mesh = app.add_subcommand("mesh", "read CANDIDE-3 and report the tracked cut of it");
    mesh->add_option("--wfm", wfm, "the CANDIDE-3 .wfm file")->capture_default_str();
    std::string points, image, drawScheme, out = "/tmp/aam-points.png";
    auto* draw = app.add_subcommand("draw", "picture an annotated image with its points numbered");
    draw->add_option("--points", points, "the .asf or .pts file")->required();
    draw->add_option("--image", image, "the image it annotates")->required();
    draw->add_option("--scheme", drawScheme,
                     "label each point with its CANDIDE vertex: imm, fgnet, ibug");
    draw->add_option("--out", out, "the PNG to write")->capture_default_str();
    FitRequest fitRequest{wfm, "imm", {}, "", "", false};
    auto* fit = app.add_subcommand("fit", "fit the tracked CANDIDE to one annotated image (5.3.1)");
    fit->add_option("--wfm", fitRequest.wfm, "the CANDIDE-3 .wfm file")->capture_default_str();
    fit->add_option("--scheme", fitRequest.scheme, "the annotation's scheme: imm, fgnet, ibug")
        ->capture_default_str();
    fit->add_option("--points", fitRequest.points, "the .asf or .pts files")->required();
    fit->add_option("--image", fitRequest.image, "the image the first file annotates (with --out)");
    fit->add_option("--out", fitRequest.out,
                    "a PNG of the first file's fitted mesh over its image");
    fit->add_flag("--per-point", fitRequest.perPoint, "the mean residual of each CANDIDE vertex");
    FitRequest shapesRequest{wfm, "imm", {}, "", "", false};
    auto* shapes = app.add_subcommand(
        "shapes", "synthesize the training shapes from the fits and align them (5.3.1)");
    shapes->add_option("--wfm", shapesRequest.wfm, "the CANDIDE-3 .wfm file")
        ->capture_default_str();
    shapes
        ->add_option("--scheme", shapesRequest.scheme, "the annotations' scheme: imm, fgnet, ibug")
        ->capture_default_str();
    shapes
        ->add_option("--points", shapesRequest.points,
                     "the .asf or .pts files, one frontal image per person")
        ->required();
    shapes->add_option("--out", shapesRequest.out, "a PNG of the aligned mean shape");
    ModelRequest modelRequest{wfm, "imm", "", "", {}, {}, false, {}};
    auto* model = app.add_subcommand(
        "model", "build the model (shape and appearance, 5.3.1), write its file, evaluate it");
    model->add_option("--wfm", modelRequest.wfm, "the CANDIDE-3 .wfm file")->capture_default_str();
    model->add_option("--scheme", modelRequest.scheme, "the annotations' scheme: imm, fgnet, ibug")
        ->capture_default_str();
    model
        ->add_option("--points", modelRequest.points,
                     "the training .asf or .pts files, one frontal image per person")
        ->required();
    model->add_option("--out", modelRequest.out, "the model file to write");
    model->add_option("--evaluate", modelRequest.evaluate,
                      "annotated images of other persons to reconstruct");
    model->add_flag("--person-specific", modelRequest.personSpecific,
                    "allow evaluating persons the model saw (rows so labelled)");
    model
        ->add_option("--resolution", modelRequest.options.resolution,
                     "the mean appearance's width in pixels")
        ->capture_default_str();
    model
        ->add_option("--appearance-variance", modelRequest.options.appearanceVariance,
                     "the variance fraction the appearance modes keep")
        ->capture_default_str();
    model->add_flag("--mirrored-appearance", modelRequest.options.mirroredAppearance,
                    "each training image also mirrored in the appearance model");
    model->add_option("--picture", modelRequest.picture,
                      "a PNG of the mean appearance and its first modes");
    std::string modelFile;
    auto* inspect =
        app.add_subcommand("inspect", "read a model file as the runtime will and print its sizes");
    inspect->add_option("--model", modelFile, "the model file")->required();
    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;
    try {
        if (*model)
            return buildModelFile(modelRequest);
        if (*inspect)
            return inspectModelFile(modelFile);
        if (*shapes)
            return alignTrainingShapes(shapesRequest);
        if (*mesh)
            return describeMesh(wfm);
        if (*fit)
            return fitFiles(fitRequest);
        return drawPoints(points, image, drawScheme, out);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "aam-build: %s\n", e.what());
        return 1;
    }
}
