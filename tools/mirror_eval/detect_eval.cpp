#include "detect_eval.hpp"

#include "face_match.hpp"
#include "face_truth.hpp"
#include "vision/face_detector.hpp"
#include "vision/haar_cascade.hpp"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/objdetect.hpp>
#include <stdexcept>
#include <vector>

namespace mirror_eval {

namespace {

struct ImageFaces {
    std::string name;
    std::vector<const LandmarkFace*> faces;
};

bool sameBox(const cv::Rect& a, const vision::Rect& b)
{
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

double ratio(long a, long b)
{
    return b > 0 ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
}

}  // namespace

int runDetectEval(const DetectEvalOptions& o, std::FILE* out, std::FILE* err)
{
    try {
        if (!(o.scaleFactor > 1.0))
            throw std::runtime_error("--scale-factor must be > 1");
        if (o.minNeighbors < 0 || o.minSize < 0)
            throw std::runtime_error("--min-neighbors and --min-size must be >= 0");
        const std::vector<LandmarkFace> truth = loadLandmarkFaces(o.truth);

        // The images of the truth file, in its order.
        std::vector<ImageFaces> images;
        for (const LandmarkFace& f : truth) {
            auto it = std::find_if(images.begin(), images.end(),
                                   [&](const ImageFaces& i) { return i.name == f.image; });
            if (it == images.end()) {
                images.push_back({f.image, {}});
                it = images.end() - 1;
            }
            it->faces.push_back(&f);
        }
        if (o.maxImages > 0 && static_cast<int>(images.size()) > o.maxImages)
            images.resize(static_cast<std::size_t>(o.maxImages));

        std::vector<cv::Mat> grays;
        vision::Size largest{0, 0};
        for (const ImageFaces& i : images) {
            const std::string path = (std::filesystem::path(o.images) / i.name).string();
            if (!std::filesystem::exists(path))
                throw std::runtime_error("image " + path + ": no such file");
            cv::Mat g = cv::imread(path, cv::IMREAD_GRAYSCALE);
            if (g.empty())
                throw std::runtime_error("image " + path + ": cannot decode");
            largest.width = std::max(largest.width, g.cols);
            largest.height = std::max(largest.height, g.rows);
            grays.push_back(std::move(g));
        }

        const vision::HaarCascade cascade = vision::loadHaarCascade(o.cascade);
        vision::FaceDetectorOptions dopt;
        dopt.maxFrameSize = largest;
        dopt.scaleFactor = o.scaleFactor;
        dopt.minNeighbors = o.minNeighbors;
        dopt.minSize = {o.minSize, o.minSize};
        vision::FaceDetector ours(cascade, dopt);
        cv::CascadeClassifier peer;
        if (!peer.load(o.cascade))
            throw std::runtime_error("cascade " + o.cascade +
                                     ": cv::CascadeClassifier cannot load it");
        cv::setNumThreads(1);

        std::fprintf(
            out, "detect eval: %zu images, %zu faces of %s; cascade %s\n", images.size(),
            [&] {
                std::size_t n = 0;
                for (const auto& i : images)
                    n += i.faces.size();
                return n;
            }(),
            o.truth.c_str(), o.cascade.c_str());
        std::fprintf(out,
                     "parameters: scale factor %.3f, min neighbours %d, min size %d, full-size "
                     "images\n",
                     o.scaleFactor, o.minNeighbors, o.minSize);
        std::fprintf(out, "truth rule: %s\n", detectRuleText().c_str());
        std::fprintf(out,
                     "opencv agreement: identical boxes / (ours + opencv - identical), "
                     "cv::CascadeClassifier with the same cascade and parameters\n");
        if (o.perImage)
            std::fprintf(out, "%-28s %9s %5s %5s %7s %6s %6s %9s\n", "image", "size", "faces",
                         "ours", "correct", "missed", "opencv", "identical");

        long faces = 0, detections = 0, correct = 0, opencvBoxes = 0, identical = 0;
        long opencvCorrect = 0;
        std::vector<double> sidePerEyeMouth, offsetPerSide;
        bool overflow = false;
        for (std::size_t k = 0; k < images.size(); ++k) {
            const cv::Mat& g = grays[k];
            const vision::ConstImageView view{g.data, g.cols, g.rows, static_cast<int>(g.step),
                                              vision::PixelFormat::Gray8};
            if (ours.detect(view) < 0)
                throw std::runtime_error(images[k].name + ": " + ours.lastError());
            overflow = overflow || ours.rawHitsOverflowed();
            const std::vector<vision::Rect> mine(ours.faces().begin(), ours.faces().end());
            std::vector<cv::Rect> theirs;
            peer.detectMultiScale(g, theirs, o.scaleFactor, o.minNeighbors, 0,
                                  cv::Size(o.minSize, o.minSize));

            const Pairing p = pairDetections(mine, images[k].faces);
            for (std::size_t c = 0; c < mine.size(); ++c) {
                const int t = p.truthOfCandidate[c];
                if (t < 0)
                    continue;
                const LandmarkFace& face = *images[k].faces[static_cast<std::size_t>(t)];
                const double d = face.eyeMouthDistance();
                sidePerEyeMouth.push_back(mine[c].width / d);
                // Box centre from the face centre along the face's eye -> mouth axis.
                const vision::Point2f e = face.eyeMidpoint(), fc = face.centre();
                const double ux = (face.mouthCentre.x - e.x) / d,
                             uy = (face.mouthCentre.y - e.y) / d;
                const double bx = mine[c].x + 0.5 * mine[c].width - fc.x;
                const double by = mine[c].y + 0.5 * mine[c].height - fc.y;
                offsetPerSide.push_back((bx * ux + by * uy) / mine[c].width);
            }
            std::vector<vision::Rect> theirsAsRects;
            for (const cv::Rect& r : theirs)
                theirsAsRects.push_back({r.x, r.y, r.width, r.height});
            opencvCorrect += pairDetections(theirsAsRects, images[k].faces).matches;

            long same = 0;
            std::vector<bool> used(mine.size(), false);
            for (const cv::Rect& t : theirs) {
                for (std::size_t c = 0; c < mine.size(); ++c) {
                    if (!used[c] && sameBox(t, mine[c])) {
                        used[c] = true;
                        ++same;
                        break;
                    }
                }
            }
            faces += static_cast<long>(images[k].faces.size());
            detections += static_cast<long>(mine.size());
            correct += p.matches;
            opencvBoxes += static_cast<long>(theirs.size());
            identical += same;
            if (o.perImage) {
                char size[24];
                std::snprintf(size, sizeof size, "%dx%d", g.cols, g.rows);
                std::fprintf(out, "%-28s %9s %5zu %5zu %7d %6d %6zu %9ld\n", images[k].name.c_str(),
                             size, images[k].faces.size(), mine.size(), p.matches,
                             static_cast<int>(images[k].faces.size()) - p.matches, theirs.size(),
                             same);
            }
        }

        const double precision = ratio(correct, detections);
        const double recall = ratio(correct, faces);
        const long unionBoxes = detections + opencvBoxes - identical;
        const double agree = unionBoxes > 0 ? ratio(identical, unionBoxes) : 1.0;
        std::sort(sidePerEyeMouth.begin(), sidePerEyeMouth.end());
        std::sort(offsetPerSide.begin(), offsetPerSide.end());
        std::fprintf(out,
                     "ours:   %ld detections, %ld correct, %ld false; %ld of %ld faces found "
                     "(%ld missed)\n",
                     detections, correct, detections - correct, correct, faces, faces - correct);
        std::fprintf(out,
                     "opencv: %ld detections, %ld correct (precision %.3f, recall %.3f); "
                     "identical boxes %ld (of ours %.3f, of opencv's %.3f)\n",
                     opencvBoxes, opencvCorrect, ratio(opencvCorrect, opencvBoxes),
                     ratio(opencvCorrect, faces), identical, ratio(identical, detections),
                     ratio(identical, opencvBoxes));
        if (!sidePerEyeMouth.empty())
            std::fprintf(out,
                         "correct boxes: side / eye-mouth distance median %.2f (rule's scale "
                         "%.1f); box centre from the face centre along the eye-mouth axis, "
                         "median %.3f x side\n",
                         sidePerEyeMouth[sidePerEyeMouth.size() / 2],
                         static_cast<double>(kBoxPerEyeMouth),
                         offsetPerSide[offsetPerSide.size() / 2]);
        if (overflow)
            std::fprintf(out, "warning: raw hit list overflowed on some image (maxRawHits)\n");
        std::fprintf(out, "detect: precision=%.3f recall=%.3f agree_opencv=%.3f\n", precision,
                     recall, agree);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(err, "mirror-eval detect: %s\n", e.what());
        return 1;
    }
}

}  // namespace mirror_eval
