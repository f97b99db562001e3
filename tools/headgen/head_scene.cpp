// headgen frames and their truth (head_scene.hpp).
#include "head_scene.hpp"

#include "compositor.hpp"
#include "head_renderer.hpp"
#include "scenarios.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <stdexcept>

namespace headgen {

namespace fs = std::filesystem;

namespace {

/// The background with its own faces blurred beyond recognition: the rendered head is then the
/// only face a detector can find, so the evaluation's box is always on it.
cv::Mat withoutItsFaces(const facegen::Background& background)
{
    cv::Mat image = background.image.clone();
    for (const facegen::FaceState& f : background.faces) {
        const double side = 1.4 * f.size;
        const cv::Rect box =
            cv::Rect(static_cast<int>(f.cx - side / 2), static_cast<int>(f.cy - side / 2),
                     static_cast<int>(side), static_cast<int>(side)) &
            cv::Rect(0, 0, image.cols, image.rows);
        if (box.area() > 0)
            cv::GaussianBlur(image(box), image(box), cv::Size(), f.size / 6);
    }
    return image;
}

}  // namespace

HeadScene::HeadScene(const SceneOptions& options) : options_(options)
{
    const fs::path data(options.dataDir);
    mesh_ = vision::reduceCandideForTracking(
        aam::loadWfm((data / "candide3" / "candide3.wfm").string()));
    const std::vector<std::string> faces =
        options.faces.empty() ? heldOutImmFaces((data / "imm_face_db").string()) : options.faces;
    for (const std::string& asf : faces)
        textures_.push_back(loadHeadTexture(mesh_, asf));
    std::set<std::string> seen;
    const std::string cascade =
        options.cascade.empty() ? std::string(facegen::kDefaultCascade) : options.cascade;
    for (const facegen::ScenarioInfo& s : facegen::scenarios()) {
        if (!seen.insert(s.background).second)
            continue;
        const std::string path = (data / s.background).string();
        backgroundPaths_.push_back(path);
        backgrounds_.push_back(
            withoutItsFaces(facegen::loadBackground(path, options.motion.size, cascade)));
    }
    plans_ = planFrames(options.motion, static_cast<int>(textures_.size()),
                        static_cast<int>(backgrounds_.size()));
}

namespace {

/// The palm on the chin, across the face by `side`, fingers up the face (turned by the plan).
Hand handFor(const vision::CandideMesh& mesh, const ProjectedHead& head, const FramePlan& plan)
{
    const auto vertex = [&](int number) {
        return head.image[static_cast<std::size_t>(mesh.indexOfCandideVertex(number))];
    };
    const Eigen::Vector2d across = vertex(20) - vertex(53);  // image left to right eye corner
    const double eyes = across.norm();
    Hand h;
    h.present = true;
    h.palm = 0.5 * (vertex(10) + vertex(8)) + plan.handSide * 0.35 * across;
    h.width = 0.75 * eyes;
    h.angleDeg = plan.pose.rollDeg + plan.handAngleDeg;
    return h;
}

Eigen::Vector4d boundingBox(const std::vector<Eigen::Vector2d>& points)
{
    Eigen::Vector2d low = points.front(), high = points.front();
    for (const auto& p : points)
        low = low.cwiseMin(p), high = high.cwiseMax(p);
    return {low.x(), low.y(), high.x(), high.y()};
}

}  // namespace

HeadScene::Frame HeadScene::frame(int index) const
{
    const FramePlan& plan = plans_.at(static_cast<std::size_t>(index));
    const HeadTexture& texture = textures_[static_cast<std::size_t>(plan.texture)];
    cv::Mat canvas = backgrounds_[static_cast<std::size_t>(plan.background)].clone();
    const ProjectedHead head = projectHead(mesh_, texture.sigma, plan.pose);
    std::vector<bool> seen = drawHead(canvas, mesh_, texture, head);

    Frame f;
    f.truth.source = texture.name;
    f.truth.pose = plan.pose;
    f.truth.box = boundingBox(head.image);
    if (plan.hand) {
        f.truth.hand = handFor(mesh_, head, plan);
        const cv::Mat cover = drawHand(canvas, f.truth.hand, texture.skin);
        for (std::size_t v = 0; v < seen.size(); ++v) {
            const cv::Point p(static_cast<int>(std::lround(head.image[v].x())),
                              static_cast<int>(std::lround(head.image[v].y())));
            if (seen[v] && p.inside(cv::Rect(0, 0, cover.cols, cover.rows)))
                seen[v] = cover.at<float>(p) < 0.5f;
        }
    }
    for (std::size_t v = 0; v < head.image.size(); ++v)
        f.truth.vertices.push_back({mesh_.candideNumber[v], head.image[v], seen[v]});

    cv::Mat noise(canvas.size(), CV_32FC3);
    cv::RNG rng(static_cast<std::uint64_t>(options_.motion.seed) * 1000003u +
                static_cast<std::uint64_t>(index));
    rng.fill(noise, cv::RNG::NORMAL, 0.0, kNoiseSigma);
    canvas += noise;
    canvas.convertTo(f.bgr, CV_8UC3);
    return f;
}

void writeScene(const HeadScene& scene, const SceneOptions& options, const std::string& outDir)
{
    const fs::path out(outDir);
    for (const char* sub : {"frames", "truth"}) {
        fs::create_directories(out / sub);
        for (const auto& e : fs::directory_iterator(out / sub))
            fs::remove(e.path());
    }
    for (int i = 0; i < scene.frames(); ++i) {
        char stem[16];
        std::snprintf(stem, sizeof stem, "%06d", i);
        const HeadScene::Frame f = scene.frame(i);
        const std::string png = (out / "frames" / (std::string(stem) + ".png")).string();
        if (!cv::imwrite(png, f.bgr))
            throw std::runtime_error(png + ": cannot write");
        std::ofstream truth(out / "truth" / (std::string(stem) + ".txt"));
        writeHeadTruth(truth, f.truth);
        if (!truth)
            throw std::runtime_error((out / "truth").string() + ": cannot write " + stem + ".txt");
    }
    std::ofstream readme(out / "README.txt");
    const MotionOptions& m = options.motion;
    readme << "headgen " << (m.sequence ? "sequence" : "single frames") << ": " << scene.frames()
           << " frames " << m.size.width << "x" << m.size.height << ", seed " << m.seed
           << ", |yaw| <= " << m.maxYawDeg << ", |pitch| <= " << m.maxPitchDeg
           << ", |roll| <= " << m.maxRollDeg << " degrees\n"
           << "textures (IMM, research only):";
    for (const HeadTexture& t : scene.textures())
        readme << ' ' << t.name;
    readme << "\nbackgrounds:";
    for (const std::string& b : scene.backgroundPaths())
        readme << ' ' << b;
    readme << "\ntruth format: tools/headgen/head_truth.hpp\n";
}

}  // namespace headgen
