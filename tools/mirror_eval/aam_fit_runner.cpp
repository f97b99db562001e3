#include "aam_fit_runner.hpp"

#include "mean_shape_baseline.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace mirror_eval {

AamFitRunner::AamFitRunner(const std::string& modelPath, const std::string& dataDir,
                           DlibPeer& boxes)
{
    vision::AamModelFile file = vision::loadAamModel(modelPath);
    if (!file.ok)
        throw std::runtime_error(file.problem);
    model_ = std::move(file.model);
    // The mean shape's box in dlib's box: its width and its centre below the box centre, both
    // over the box width (the baseline's offsets are per vertex, in box widths).
    const MeanShapeBaseline baseline(dataDir, boxes);
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (const Eigen::Vector2d& o : baseline.offsets()) {
        x0 = std::min(x0, o.x()), x1 = std::max(x1, o.x());
        y0 = std::min(y0, o.y()), y1 = std::max(y1, o.y());
    }
    placement_.widthOverBox = static_cast<float>(x1 - x0);
    placement_.downOverBox = static_cast<float>(0.5 * (y0 + y1));
    vision::TrackedFaceFitterOptions options;
    options.placement = placement_;
    fitter_ = std::make_unique<vision::TrackedFaceFitter>(model_, options);
}

std::string AamFitRunner::label() const
{
    char text[128];
    std::snprintf(
        text, sizeof text, "aam fit (TrackedFaceFitter; on dlib's boxes: width %.3f, down %.3f)",
        static_cast<double>(placement_.widthOverBox), static_cast<double>(placement_.downOverBox));
    return text;
}

HeadFit AamFitRunner::fit(const cv::Mat& grey, const FaceBoxPx& box)
{
    vision::TrackedFace face;
    face.id = 1;
    face.centre = {static_cast<float>(box.centre().x()), static_cast<float>(box.centre().y())};
    face.size = static_cast<float>(box.width());
    face.state = vision::FaceState::Confirmed;
    const vision::ConstImageView view{grey.data, grey.cols, grey.rows,
                                      static_cast<int>(grey.step[0]), vision::PixelFormat::Gray8};
    fitter_->process(view, {&face, 1});
    const vision::FaceFit& f = fitter_->fits()[0];
    HeadFit h;
    h.held = f.ok();
    for (int v = 0; v < f.vertexCount; ++v)
        h.vertices.emplace_back(f.vertices[static_cast<std::size_t>(v)].x,
                                f.vertices[static_cast<std::size_t>(v)].y);
    h.angles = HeadAngles{f.yawDegrees, f.pitchDegrees, f.rollDegrees};
    h.animation = f.animation;
    h.iterations = f.iterations;
    return h;
}

}  // namespace mirror_eval
