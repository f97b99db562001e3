#include "training_image.hpp"

#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <vector>

namespace aam {

namespace fs = std::filesystem;

std::string annotatedImagePath(const std::string& annotationPath, const Annotation& annotation)
{
    const fs::path file(annotationPath);
    std::vector<fs::path> candidates;
    if (!annotation.hostImage.empty())
        candidates.push_back(file.parent_path() / annotation.hostImage);
    for (const char* ext : {".jpg", ".png"}) {
        candidates.push_back(fs::path(file).replace_extension(ext));
        candidates.push_back(file.parent_path().parent_path() / "images" / file.stem().concat(ext));
    }
    std::error_code ec;
    for (const fs::path& c : candidates) {
        if (fs::is_regular_file(c, ec))
            return c.string();
    }
    throw std::runtime_error(
        annotationPath + ": no image beside it (its host image, or the same name as .jpg or .png)");
}

cv::Mat loadGreyImage(const std::string& path)
{
    const vision::BoundedFile file = vision::readBoundedFile(path, vision::limits::kImageFileBytes);
    if (file.status != vision::BoundedFile::Status::Ok)
        throw std::runtime_error(path + ": " + file.problem);
    const cv::Mat bytes(1, static_cast<int>(file.text.size()), CV_8U,
                        const_cast<char*>(file.text.data()));
    cv::Mat grey;
    try {
        grey = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
    } catch (const cv::Exception& e) {
        throw std::runtime_error(path + ": not an image OpenCV can read (" + e.err + ")");
    }
    if (grey.empty())
        throw std::runtime_error(path + ": not an image OpenCV can read");
    return grey;
}

std::string personOf(const std::string& path)
{
    const std::string stem = fs::path(path).stem().string();
    const auto dash = stem.find_first_of("-_");
    return dash == std::string::npos ? stem : stem.substr(0, dash);
}

}  // namespace aam
