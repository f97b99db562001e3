// Textures for rendered heads: IMM photographs through their CANDIDE fits (§5, 5.3.1).
#include "head_texture.hpp"

#include "annotation_files.hpp"
#include "annotation_schemes.hpp"
#include "candide_fit.hpp"
#include "training_image.hpp"

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace headgen {

namespace {

/// Mean colour of a small patch under each eye's outer half (cheek skin, no hair or shadow).
cv::Scalar cheekColour(const vision::CandideMesh& mesh, const cv::Mat& photo,
                       const std::vector<Eigen::Vector2d>& uv)
{
    cv::Scalar sum(0, 0, 0);
    int count = 0;
    for (const auto& [eye, nostril] : {std::pair{20, 26}, std::pair{53, 59}}) {
        const int e = mesh.indexOfCandideVertex(eye), n = mesh.indexOfCandideVertex(nostril);
        if (e < 0 || n < 0)
            continue;
        const Eigen::Vector2d c =
            0.5 * (uv[static_cast<std::size_t>(e)] + uv[static_cast<std::size_t>(n)]);
        const int r = std::max(
            2,
            static_cast<int>(
                0.15 * (uv[static_cast<std::size_t>(e)] - uv[static_cast<std::size_t>(n)]).norm()));
        const cv::Rect patch =
            cv::Rect(static_cast<int>(c.x()) - r, static_cast<int>(c.y()) - r, 2 * r, 2 * r) &
            cv::Rect(0, 0, photo.cols, photo.rows);
        if (patch.area() == 0)
            continue;
        sum += cv::mean(photo(patch));
        ++count;
    }
    return count ? sum / count : cv::Scalar(120, 140, 180);
}

}  // namespace

HeadTexture loadHeadTexture(const vision::CandideMesh& mesh, const std::string& asfPath)
{
    const aam::Annotation annotation = aam::loadAnnotation(asfPath);
    const aam::CandideFit fit =
        aam::fitCandide(mesh, aam::markedPoints(aam::immScheme(), annotation, mesh));
    HeadTexture t;
    t.name = std::filesystem::path(asfPath).stem().string();
    const std::string image = aam::annotatedImagePath(asfPath, annotation);
    t.photo = cv::imread(image, cv::IMREAD_COLOR);
    if (t.photo.empty())
        throw std::runtime_error(image + ": cannot read the photograph");
    t.uv = aam::projectedVertices(mesh, fit);
    t.sigma = fit.sigma;
    t.skin = cheekColour(mesh, t.photo, t.uv);
    return t;
}

bool heldOutOfDemoModel(const std::string& path)
{
    const std::string person = aam::personOf(path);
    int number = 0;
    for (char c : person) {
        if (c < '0' || c > '9')
            return false;
        number = 10 * number + (c - '0');
    }
    return !person.empty() && number % 4 == 0;
}

std::vector<std::string> heldOutImmFaces(const std::string& immDir)
{
    std::vector<std::string> paths;
    for (const auto& e : std::filesystem::directory_iterator(immDir)) {
        const std::string name = e.path().filename().string();
        if (e.path().extension() == ".asf" && name.size() > 3 && name.substr(2, 2) == "-1" &&
            heldOutOfDemoModel(name))
            paths.push_back(e.path().string());
    }
    std::sort(paths.begin(), paths.end());
    if (paths.empty())
        throw std::runtime_error(immDir +
                                 ": no IMM photographs of the held-out persons (04-1m.asf ...)");
    return paths;
}

}  // namespace headgen
