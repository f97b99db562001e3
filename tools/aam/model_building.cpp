// The model's steps in the text's order (5.3.1): shapes, alignment, shape modes, frame, warps,
// appearance modes.
#include "model_building.hpp"

#include "annotation_files.hpp"
#include "appearance_warp.hpp"
#include "mirrored_training.hpp"
#include "training_image.hpp"

#include <algorithm>
#include <stdexcept>

namespace aam {

namespace {

std::vector<float> asFloats(const Eigen::MatrixXd& m)
{
    std::vector<float> out(static_cast<std::size_t>(m.size()));
    std::transform(m.data(), m.data() + m.size(), out.begin(),
                   [](double v) { return static_cast<float>(v); });
    return out;
}

}  // namespace

AlignedShapes alignedTrainingShapes(const vision::CandideMesh& face,
                                    const std::vector<CandideFit>& fits, SynthesisOptions synthesis)
{
    std::vector<Shape2d> shapes;
    for (const CandideFit& fit : fits) {
        for (auto& s : synthesizeShapes(face, fit, synthesis))
            shapes.push_back(std::move(s));
        ++synthesis.seed;  // each image its own poses
    }
    const Shape2d frontal =
        posedShape(face, fits.front(), 0, 0, std::vector<float>(fits.front().tau.size(), 0.f));
    AlignmentOptions alignment;
    alignment.reference = &frontal;
    return alignShapes(shapes, alignment);
}

FittedImage fitAnnotatedImage(const vision::CandideMesh& face, const AnnotationScheme& scheme,
                              const std::string& path)
{
    FittedImage image;
    image.annotationPath = path;
    image.person = personOf(path);
    const Annotation annotation = loadAnnotation(path);
    image.fit = fitCandide(face, markedPoints(scheme, annotation, face));
    image.shape = projectedVertices(face, image.fit);
    image.imagePath = annotatedImagePath(path, annotation);
    image.grey = loadGreyImage(image.imagePath);
    return image;
}

BuiltModel buildModel(const vision::CandideMesh& face, const std::vector<FittedImage>& training,
                      const ModelOptions& options)
{
    if (training.size() < 2)
        throw std::invalid_argument("model: " + std::to_string(training.size()) +
                                    " training images; at least 2 needed");
    BuiltModel built;
    built.face = face;
    for (const FittedImage& image : training) {
        if (std::find(built.persons.begin(), built.persons.end(), image.person) ==
            built.persons.end())
            built.persons.push_back(image.person);
    }
    std::vector<CandideFit> fits;
    for (const FittedImage& image : training)
        fits.push_back(image.fit);
    built.aligned = alignedTrainingShapes(face, fits, options.synthesis);
    built.shape = shapeModes(built.aligned, options.shapeVariance);
    built.frame = appearanceFrame(face, built.shape.mean, options.resolution);
    std::vector<Eigen::VectorXd> warped;
    const std::vector<int> partners =
        options.mirroredAppearance ? mirrorPartners(face) : std::vector<int>{};
    for (const FittedImage& image : training) {
        warped.push_back(warpToFrame(image.grey, image.shape, face, built.frame));
        if (options.mirroredAppearance)
            warped.push_back(warpToFrame(mirroredImage(image.grey),
                                         mirroredShape(image.shape, partners, image.grey.cols),
                                         face, built.frame));
    }
    built.appearance = appearanceModes(warped, options.appearanceVariance);
    return built;
}

vision::AamModel modelForFile(const BuiltModel& built)
{
    vision::AamModel m;
    m.mesh = built.face;
    for (const auto& p : built.frame.meanShape) {
        m.meanShape.push_back(static_cast<float>(p.x()));
        m.meanShape.push_back(static_cast<float>(p.y()));
    }
    // Orthonormal modes stay orthonormal under the frame's scaling; their variances scale by its
    // square.
    m.shapeModes = asFloats(built.shape.modes);
    m.shapeVariances = asFloats(built.shape.variances * (built.frame.scale * built.frame.scale));
    m.frameWidth = built.frame.width;
    m.frameHeight = built.frame.height;
    for (const FramePixel& px : built.frame.pixels) {
        m.pixels.push_back({static_cast<std::uint16_t>(px.x), static_cast<std::uint16_t>(px.y),
                            static_cast<std::uint16_t>(px.triangle)});
    }
    m.meanAppearance = asFloats(built.appearance.mean);
    m.appearanceModes = asFloats(built.appearance.modes);
    m.appearanceVariances = asFloats(built.appearance.variances);
    return m;
}

}  // namespace aam
