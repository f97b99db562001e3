// mirror-eval people (people_eval.hpp): recognition from the fitted AAM's signature (§6).
#include "people_eval.hpp"

#include "aam_eval_report.hpp"
#include "annotation_files.hpp"
#include "vision/aam_model.hpp"
#include "vision/face_detector.hpp"
#include "vision/haar_cascade.hpp"
#include "vision/person_gallery.hpp"
#include "vision/tracked_face_fitter.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <vector>

namespace mirror_eval {

namespace {

namespace fs = std::filesystem;
using aam_report::UsageError;

constexpr int kImmPersons = 40, kImmTypes = 6;
constexpr int kFranck = 1000;  ///< franck's id in the gallery (IMM's persons are 1..40)

/// The persons scripts/dev leaves out of the demo model: every fourth.
bool heldOut(int person)
{
    return person % 4 == 0;
}

vision::ConstImageView viewOf(const cv::Mat& grey)
{
    return {grey.data, grey.cols, grey.rows, static_cast<int>(grey.step[0]),
            vision::PixelFormat::Gray8};
}

/// The face tracker's detector as the appliance runs it (the frame shrunk by 2, faces from 24
/// px), its largest face in the full image's pixels as a shown track.
class BoxFinder {
public:
    explicit BoxFinder(const std::string& cascadePath)
        : cascade_(vision::loadHaarCascade(cascadePath)), detector_(cascade_, optionsFor())
    {
    }

    /// The largest face, or with `near` the largest whose box holds that point.
    std::optional<vision::TrackedFace> largest(const cv::Mat& grey, int id,
                                               std::optional<vision::Point2f> near = std::nullopt)
    {
        cv::resize(grey, half_, {grey.cols / 2, grey.rows / 2}, 0, 0, cv::INTER_AREA);
        if (half_.cols > kMaxSide.width || half_.rows > kMaxSide.height ||
            detector_.detect(viewOf(half_)) < 0)
            return std::nullopt;
        std::optional<vision::TrackedFace> best;
        for (const vision::Rect& r : detector_.faces()) {
            const float side = 2.f * static_cast<float>(r.width);
            if (best && side <= best->size)
                continue;
            vision::TrackedFace f;
            f.id = id;
            f.centre = {
                2.f * (static_cast<float>(r.x) + 0.5f * static_cast<float>(r.width)) - 0.5f,
                2.f * (static_cast<float>(r.y) + 0.5f * static_cast<float>(r.height)) - 0.5f};
            f.size = side;
            f.state = vision::FaceState::Confirmed;
            if (near && (std::abs(near->x - f.centre.x) > 0.5f * side ||
                         std::abs(near->y - f.centre.y) > 0.5f * side))
                continue;
            best = f;
        }
        return best;
    }

private:
    static constexpr vision::Size kMaxSide{400, 300};
    static vision::FaceDetectorOptions optionsFor()
    {
        vision::FaceDetectorOptions o;
        o.maxFrameSize = kMaxSide;
        o.minSize = {24, 24};
        return o;
    }
    vision::HaarCascade cascade_;
    vision::FaceDetector detector_;
    cv::Mat half_;
};

cv::Mat readGreyImage(const fs::path& path)
{
    cv::Mat grey = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    if (grey.empty())
        throw std::runtime_error(path.string() + ": cannot read the image");
    return grey;
}

/// A still image as the appliance would see a person standing still: one track fitted frame
/// after frame until its signature settles (or maxFits). Empty (samples 0) without a box or
/// without an ok fit after the shape units froze.
vision::FaceSignature signatureOfStill(const cv::Mat& grey, BoxFinder& boxes,
                                       vision::TrackedFaceFitter& fitter, int maxFits,
                                       bool* boxFound = nullptr, std::FILE* log = nullptr,
                                       const char* name = "")
{
    fitter.reset();
    const std::optional<vision::TrackedFace> face = boxes.largest(grey, 1);
    if (boxFound != nullptr)
        *boxFound = face.has_value();
    if (!face)
        return {};
    for (int i = 0; i < maxFits; ++i) {
        fitter.process(viewOf(grey), {&*face, 1});
        const vision::FaceFit& fit = fitter.fits()[0];
        if (fit.signatureSettled)
            break;
        if (log != nullptr && i + 1 == maxFits)
            std::fprintf(log,
                         "  %s: not settled after %d fits: last fit %s (error %.2f, yaw %.1f)\n",
                         name, maxFits, fit.status(), static_cast<double>(fit.fitError),
                         static_cast<double>(fit.yawDegrees));
    }
    return fitter.fits()[0].signature;
}

/// Two signatures as one, each weighted by its samples (a person enrolled from two photographs).
vision::FaceSignature merged(const vision::FaceSignature& a, const vision::FaceSignature& b)
{
    if (a.samples == 0)
        return b;
    if (b.samples == 0 || a.appearanceCount != b.appearanceCount)
        return a;
    vision::FaceSignature m = a;
    const float wa = static_cast<float>(a.samples) / static_cast<float>(a.samples + b.samples);
    for (std::size_t i = 0; i < m.shapeUnits.size(); ++i)
        m.shapeUnits[i] = wa * a.shapeUnits[i] + (1.f - wa) * b.shapeUnits[i];
    for (std::size_t i = 0; i < m.appearance.size(); ++i)
        m.appearance[i] = wa * a.appearance[i] + (1.f - wa) * b.appearance[i];
    if (a.textureCount == b.textureCount)
        for (std::size_t i = 0; i < m.texture.size(); ++i)
            m.texture[i] = static_cast<std::uint8_t>(
                std::lround(wa * a.texture[i] + (1.f - wa) * b.texture[i]));
    m.samples = a.samples + b.samples;
    return m;
}

struct Rate {
    int hits = 0, total = 0;
    void add(bool hit) { hits += hit ? 1 : 0, ++total; }
    double value() const
    {
        return total > 0 ? static_cast<double>(hits) / total : aam_report::kNan;
    }
    std::string text() const
    {
        return total > 0 ? aam_report::number(value(), "%.3f") + " (" + std::to_string(hits) + "/" +
                               std::to_string(total) + ")"
                         : "-";
    }
};

std::vector<int> enrolTypes(const std::string& text)
{
    if (text == "1")
        return {1};
    if (text == "1,2")
        return {1, 2};
    throw UsageError("--enrol " + text + ": give 1 or 1,2");
}

struct ImmResult {
    Rate frontal, turned;  ///< all persons (the final line)
    Rate heldFrontal, heldTurned;
    Rate falseAccept, heldFalseAccept;
    bool ran = false;
};

void dumpSignature(std::ostream& csv, const std::string& who, int person, int type,
                   const vision::FaceSignature& s)
{
    csv << who << ',' << person << ',' << type << ',' << s.samples;
    for (float v : s.shapeUnits)
        csv << ',' << v;
    csv << ',' << s.appearanceCount;
    for (int i = 0; i < s.appearanceCount; ++i)
        csv << ',' << s.appearance[static_cast<std::size_t>(i)];
    csv << ',' << s.textureCount;
    for (int i = 0; i < s.textureCount; ++i)
        csv << ',' << static_cast<int>(s.texture[static_cast<std::size_t>(i)]);
    csv << '\n';
}

/// How much each signature value varies between one person's photographs (std of the
/// deviations from the person's mean), over the persons the model was built from only: the
/// gallery's whitening tables (PersonGalleryOptions::appearanceSpread, shapeSpread) for this model.
void printSpread(const std::vector<std::array<vision::FaceSignature, kImmTypes + 1>>& signatures,
                 std::FILE* out)
{
    std::vector<double> shape(vision::kAamShapeUnits, 0.0), appearance;
    int count = 0;
    for (std::size_t person = 1; person < signatures.size(); ++person) {
        if (heldOut(static_cast<int>(person)))
            continue;
        std::vector<const vision::FaceSignature*> own;
        for (const vision::FaceSignature& s : signatures[person])
            if (s.samples > 0)
                own.push_back(&s);
        if (own.size() < 2)
            continue;
        const auto modes = static_cast<std::size_t>(own.front()->appearanceCount);
        appearance.resize(std::max(appearance.size(), modes), 0.0);
        auto add = [&](auto value, std::vector<double>& sums, std::size_t n) {
            for (std::size_t i = 0; i < n; ++i) {
                double mean = 0;
                for (const auto* s : own)
                    mean += value(*s, i);
                mean /= static_cast<double>(own.size());
                for (const auto* s : own)
                    sums[i] += (value(*s, i) - mean) * (value(*s, i) - mean);
            }
        };
        add([](const vision::FaceSignature& s, std::size_t i) { return double{s.shapeUnits[i]}; },
            shape, shape.size());
        add([](const vision::FaceSignature& s, std::size_t i) { return double{s.appearance[i]}; },
            appearance, modes);
        count += static_cast<int>(own.size());
    }
    if (count == 0)
        return;
    std::fprintf(out, "within-person spread, persons in the model (%d photographs): shape units",
                 count);
    for (double v : shape)
        std::fprintf(out, " %.3f", std::sqrt(v / count));
    std::fprintf(out, "; appearance");
    for (double v : appearance)
        std::fprintf(out, " %.2f", std::sqrt(v / count));
    std::fprintf(out, "\n");
}

ImmResult runImm(const PeopleEvalOptions& o, const fs::path& folder, BoxFinder& boxes,
                 vision::TrackedFaceFitter& fitter,
                 const vision::PersonGalleryOptions& galleryOptions, std::ostream* csv,
                 std::FILE* out)
{
    const std::vector<int> enrolled = enrolTypes(o.enrol);
    // signatures[person][type]
    std::vector<std::array<vision::FaceSignature, kImmTypes + 1>> signatures(kImmPersons + 1);
    std::vector<std::array<bool, kImmTypes + 1>> present(kImmPersons + 1);
    int images = 0, noSignature = 0;
    std::array<int, kImmTypes + 1> noBox{}, noFit{};
    for (int person = 1; person <= std::min(o.persons, kImmPersons); ++person)
        for (int type = 1; type <= kImmTypes; ++type)
            for (const char sex : {'m', 'f'}) {
                char name[32];
                std::snprintf(name, sizeof name, "%02d-%d%c.jpg", person, type, sex);
                const fs::path path = folder / name;
                if (!fs::exists(path))
                    continue;
                present[person][type] = true;
                ++images;
                bool box = false;
                const auto& s = signatures[person][type] =
                    signatureOfStill(readGreyImage(path), boxes, fitter, o.maxFits, &box,
                                     o.perImage ? out : nullptr, name);
                noSignature += s.samples == 0 ? 1 : 0;
                noBox[type] += box ? 0 : 1;
                noFit[type] += box && s.samples == 0 ? 1 : 0;
                if (csv != nullptr)
                    dumpSignature(*csv, "imm", person, type, s);
            }
    if (images == 0)
        throw UsageError("IMM " + folder.string() + ": no IMM photographs (NN-Tx.jpg)");
    printSpread(signatures, out);
    std::fprintf(out,
                 "IMM %s: %d photographs, %d without a settled signature (no box or no ok "
                 "fit); enrolled from type%s %s\n",
                 folder.string().c_str(), images, noSignature, enrolled.size() > 1 ? "s" : "",
                 o.enrol.c_str());
    std::fprintf(out, "without a signature, per type (no box / no ok fit after the freeze):");
    for (int type = 1; type <= kImmTypes; ++type)
        std::fprintf(out, " %d: %d/%d", type, noBox[static_cast<std::size_t>(type)],
                     noFit[static_cast<std::size_t>(type)]);
    std::fprintf(out, "\n");
    auto enrolmentOf = [&](int person) {
        vision::FaceSignature e{};
        for (int type : enrolled)
            e = merged(e, signatures[person][static_cast<std::size_t>(type)]);
        return e;
    };
    const bool isEnrolType[kImmTypes + 1] = {false,
                                             std::count(enrolled.begin(), enrolled.end(), 1) > 0,
                                             std::count(enrolled.begin(), enrolled.end(), 2) > 0,
                                             false,
                                             false,
                                             false,
                                             false};

    // Rank-1: everybody enrolled, each other photograph matched; the nearest must be its person.
    vision::PersonGallery all(galleryOptions);
    for (int person = 1; person <= kImmPersons; ++person)
        all.enrol(person, enrolmentOf(person));
    std::map<int, Rate> inModel, held;
    ImmResult r;
    r.ran = true;
    for (int person = 1; person <= kImmPersons; ++person)
        for (int type = 1; type <= kImmTypes; ++type) {
            if (!present[person][type] || isEnrolType[type])
                continue;
            const vision::PersonMatch m = all.match(signatures[person][type]);
            const bool hit = m.nearestId == person;
            (heldOut(person) ? held : inModel)[type].add(hit);
            const bool frontal = type == 1 || type == 2 || type == 5;
            const bool turned = type == 3 || type == 4;
            if (frontal)
                r.frontal.add(hit);
            if (turned)
                r.turned.add(hit);
            if (frontal && heldOut(person))
                r.heldFrontal.add(hit);
            if (turned && heldOut(person))
                r.heldTurned.add(hit);
        }
    std::fprintf(out, "rank-1 (the nearest of the %d enrolled is the person):\n", all.size());
    std::fprintf(out, "%-5s %-22s %-22s\n", "type", "in the model", "held out");
    for (int type = 1; type <= kImmTypes; ++type)
        if (inModel.count(type) + held.count(type) > 0)
            std::fprintf(out, "%-5d %-22s %-22s\n", type, inModel[type].text().c_str(),
                         held[type].text().c_str());

    // False accepts: half the persons enrolled, every photograph of the others must be a guest;
    // each half in turn. The enrolled half's own probes are accepted as themselves or not.
    Rate trueAccept, heldTrueAccept;
    for (int half = 0; half < 2; ++half) {
        vision::PersonGallery gallery(galleryOptions);
        for (int person = 1; person <= kImmPersons; ++person)
            if (person % 2 == half)
                gallery.enrol(person, enrolmentOf(person));
        for (int person = 1; person <= kImmPersons; ++person)
            for (int type = 1; type <= kImmTypes; ++type) {
                if (!present[person][type])
                    continue;
                const vision::PersonMatch m = gallery.match(signatures[person][type]);
                if (person % 2 != half) {
                    r.falseAccept.add(m.personId != 0);
                    if (heldOut(person))
                        r.heldFalseAccept.add(m.personId != 0);
                } else if (!isEnrolType[type]) {
                    trueAccept.add(m.personId == person);
                    if (heldOut(person))
                        heldTrueAccept.add(m.personId == person);
                }
            }
    }
    std::fprintf(out,
                 "half enrolled (odd, then even persons), acceptScore %.3f: false accept %s "
                 "(held-out strangers %s); enrolled probes accepted as themselves %s (held out "
                 "%s)\n",
                 static_cast<double>(galleryOptions.acceptScore), r.falseAccept.text().c_str(),
                 r.heldFalseAccept.text().c_str(), trueAccept.text().c_str(),
                 heldTrueAccept.text().c_str());
    return r;
}

struct FgnetResult {
    Rate kept;
    bool ran = false;
};

/// The centre of frame `frame`'s annotated points in `truth` (NAME.pts beside NAME.jpg), when
/// there is a truth folder: the face the sequence is about, among the detector's faces.
std::optional<vision::Point2f> truthCentre(const std::string& truth, const fs::path& frame)
{
    if (truth.empty())
        return std::nullopt;
    const fs::path pts = fs::path(truth) / frame.filename().replace_extension(".pts");
    if (!fs::exists(pts))
        return std::nullopt;
    const aam::Annotation a = aam::loadAnnotation(pts.string());
    if (a.points.empty())
        return std::nullopt;
    double x0 = 1e30, x1 = -1e30, y0 = 1e30, y1 = -1e30;
    for (const Eigen::Vector2d& p : a.points) {
        x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
        y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    }
    return vision::Point2f{static_cast<float>(0.5 * (x0 + x1)),
                           static_cast<float>(0.5 * (y0 + y1))};
}

FgnetResult runFgnet(const PeopleEvalOptions& o, const fs::path& folder, BoxFinder& boxes,
                     vision::TrackedFaceFitter& fitter, vision::PersonGallery& gallery,
                     std::ostream* csv, std::FILE* out)
{
    std::vector<fs::path> frames;
    for (const auto& e : fs::directory_iterator(folder)) {
        const std::string ext = e.path().extension().string();
        if (ext == ".jpg" || ext == ".png" || ext == ".bmp")
            frames.push_back(e.path());
    }
    std::sort(frames.begin(), frames.end());
    if (o.maxFrames > 0 && static_cast<int>(frames.size()) > o.maxFrames)
        frames.resize(static_cast<std::size_t>(o.maxFrames));
    if (static_cast<int>(frames.size()) <= o.enrolFrames)
        throw UsageError("--frames " + folder.string() + ": " + std::to_string(frames.size()) +
                         " frames; more than --enrol-frames (" + std::to_string(o.enrolFrames) +
                         ") needed");
    FgnetResult r;
    r.ran = true;
    // Enrolment: one track over the first frames, collecting every ok fit's signature.
    fitter.reset();
    bool asked = false;
    for (int f = 0; f < o.enrolFrames; ++f) {
        const fs::path& path = frames[static_cast<std::size_t>(f)];
        const cv::Mat grey = readGreyImage(path);
        const std::optional<vision::TrackedFace> face =
            boxes.largest(grey, 1, truthCentre(o.truth, path));
        if (!face)
            continue;  // not seen this frame: the track is kept, as the tracker would
        fitter.process(viewOf(grey), {&*face, 1});
        if (!asked)
            asked = fitter.collectSignature(1, o.enrolFrames);
    }
    const vision::FaceSignature franck =
        fitter.fits().empty() ? vision::FaceSignature{} : fitter.fits()[0].signature;
    if (csv != nullptr)
        dumpSignature(*csv, "fgnet-enrol", kFranck, 0, franck);
    if (!gallery.enrol(kFranck, franck)) {
        std::fprintf(out, "FGNet %s: franck could not be enrolled (no ok fit in frames 0-%d)\n",
                     folder.string().c_str(), o.enrolFrames - 1);
        return r;
    }
    // Recognition: each window a new track, matched once its signature settles.
    int named = 0;
    for (int start = o.enrolFrames; start < static_cast<int>(frames.size()); start += o.window) {
        fitter.reset();
        const int id = 2 + start;
        vision::FaceSignature settled{};
        const int end = std::min(start + o.window, static_cast<int>(frames.size()));
        for (int f = start; f < end; ++f) {
            const fs::path& path = frames[static_cast<std::size_t>(f)];
            const cv::Mat grey = readGreyImage(path);
            const std::optional<vision::TrackedFace> face =
                boxes.largest(grey, id, truthCentre(o.truth, path));
            if (!face)
                continue;
            fitter.process(viewOf(grey), {&*face, 1});
            if (fitter.fits()[0].signatureSettled) {
                settled = fitter.fits()[0].signature;
                break;
            }
        }
        const vision::PersonMatch m = gallery.match(settled);
        r.kept.add(m.personId == kFranck);
        named += m.nearestId == kFranck ? 1 : 0;
        if (csv != nullptr)
            dumpSignature(*csv, "fgnet", kFranck, start, settled);
        std::fprintf(out, "  frames %d-%d: %s (score %.3f, nearest %d at %.3f)\n", start, end - 1,
                     settled.samples == 0    ? "no settled signature"
                     : m.personId == kFranck ? "franck"
                     : m.personId == 0       ? "a guest"
                                             : "someone else",
                     static_cast<double>(m.score), m.nearestId,
                     static_cast<double>(m.nearestScore));
    }
    std::fprintf(out,
                 "FGNet %s%s: franck enrolled from frames 0-%d (%d fits) beside %d IMM persons; "
                 "windows of %d frames accepted as franck %s, nearest franck %d\n",
                 folder.string().c_str(),
                 o.truth.empty() ? " (the largest face)" : " (the face holding the truth's centre)",
                 o.enrolFrames - 1, franck.samples, gallery.size() - 1, o.window,
                 r.kept.text().c_str(), named);
    return r;
}

/// facegen's moving face 1 in a frame's truth file (`id cx cy size roll_deg moving`), as the
/// tracker's shown face (facegen's box is the detector's convention, its roll the face's).
std::optional<vision::TrackedFace> composedFace(const fs::path& truth, int id)
{
    std::ifstream in(truth);
    int faceId = 0, moving = 0;
    float cx = 0, cy = 0, size = 0, roll = 0;
    while (in >> faceId >> cx >> cy >> size >> roll >> moving)
        if (faceId == 1 && moving == 1) {
            vision::TrackedFace f;
            f.id = id;
            f.centre = {cx, cy};
            f.size = size;
            f.rollDegrees = roll;
            f.state = vision::FaceState::Confirmed;
            return f;
        }
    return std::nullopt;
}

/// A facegen sequence's moving face (someone else: an IMM person) through the same windows as
/// franck's: each settled signature must not be accepted as franck.
Rate runStranger(const PeopleEvalOptions& o, const fs::path& folder,
                 vision::TrackedFaceFitter& fitter, const vision::PersonGallery& gallery,
                 std::FILE* out)
{
    std::vector<fs::path> frames;
    for (const auto& e : fs::directory_iterator(folder / "frames"))
        if (e.path().extension() == ".png")
            frames.push_back(e.path());
    std::sort(frames.begin(), frames.end());
    if (frames.empty())
        throw UsageError("--stranger " + folder.string() + ": no frames/*.png (a facegen folder)");
    Rate notFranck;
    int settledWindows = 0;
    std::map<int, int> named;
    for (std::size_t start = 0; start < frames.size();
         start += static_cast<std::size_t>(o.window)) {
        fitter.reset();
        vision::FaceSignature settled{};
        const std::size_t end = std::min(start + static_cast<std::size_t>(o.window), frames.size());
        for (std::size_t f = start; f < end; ++f) {
            const fs::path truth =
                folder / "truth" / frames[f].filename().replace_extension(".txt");
            const std::optional<vision::TrackedFace> face =
                composedFace(truth, 2 + static_cast<int>(start));
            if (!face)
                continue;
            fitter.process(viewOf(readGreyImage(frames[f])), {&*face, 1});
            if (fitter.fits()[0].signatureSettled) {
                settled = fitter.fits()[0].signature;
                break;
            }
        }
        const vision::PersonMatch m = gallery.match(settled);
        notFranck.add(m.personId != kFranck);
        settledWindows += settled.samples > 0 ? 1 : 0;
        ++named[m.personId];
    }
    std::fprintf(out,
                 "facegen %s (its moving face, an IMM person): windows of %d frames not taken "
                 "for franck %s (%d with a settled signature); accepted as:",
                 folder.string().c_str(), o.window, notFranck.text().c_str(), settledWindows);
    for (const auto& [id, n] : named)
        std::fprintf(out, " %s %d", id == 0 ? "guest" : std::to_string(id).c_str(), n);
    std::fprintf(out, "\n");
    return notFranck;
}

/// What recognition adds to a face's frame while its signature collects (the appearance
/// parameters), and one match against a gallery, timed on an IMM photograph's fit.
void timeRecognition(const vision::AamModel& model, const vision::AamFitterOptions& options,
                     const cv::Mat& grey, BoxFinder& boxes, const vision::PersonGallery& gallery,
                     std::FILE* out)
{
    const std::optional<vision::TrackedFace> face = boxes.largest(grey, 1);
    if (!face)
        return;
    vision::TrackedFaceFitter placement(model);
    vision::AamFitter fitter(model, options);
    vision::AamFaceState state;
    fitter.start(state, placement.startFor(*face));
    for (int i = 0; i < 5; ++i)
        fitter.fit(viewOf(grey), state);
    std::array<float, vision::kFaceSignatureMaxAppearance> values{};
    // The machine is shared: the fastest of 15 batches of 40 calls (and the median batch).
    using Clock = std::chrono::steady_clock;
    float sink = 0.f;
    auto perCall = [&](auto&& call) {
        constexpr int kBatches = 15, kRuns = 40;
        std::vector<double> ms;
        for (int b = 0; b < kBatches; ++b) {
            const auto t0 = Clock::now();
            for (int i = 0; i < kRuns; ++i)
                sink += static_cast<float>(call());
            ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count() /
                         kRuns);
        }
        std::sort(ms.begin(), ms.end());
        return std::pair{ms.front(), ms[ms.size() / 2]};
    };
    const auto all =
        perCall([&] { return fitter.appearanceParameters(viewOf(grey), state, values); });
    const auto one = perCall([&] {
        return fitter.appearanceParameters(viewOf(grey), state, std::span<float>(values.data(), 1));
    });
    std::array<std::uint8_t, vision::kFaceSignatureMaxTexture> texture{};
    const auto withTexture =
        perCall([&] { return fitter.appearanceParameters(viewOf(grey), state, values, texture); });
    vision::FaceSignature probe;
    probe.samples = 1;
    probe.appearanceCount = std::min<int>(fitter.appearanceModeCount(), values.size());
    std::copy_n(values.begin(), probe.appearanceCount, probe.appearance.begin());
    probe.textureCount = fitter.textureSize();
    std::copy_n(texture.begin(), probe.textureCount, probe.texture.begin());
    const auto match = perCall([&] { return gallery.match(probe).nearestId; });
    std::fprintf(out,
                 "cost per face: appearance parameters %.3f ms per collecting frame (median %.3f; "
                 "%d modes; the warp and error image with one mode %.3f), with the texture "
                 "descriptor (%d values) %.3f ms (median %.3f), one match against %d people %.4f "
                 "ms (checksum %d)\n",
                 all.first, all.second, fitter.appearanceModeCount(), one.first,
                 fitter.textureSize(), withTexture.first, withTexture.second, gallery.size(),
                 match.first, sink > 0.f ? 1 : 0);
}

int run(const PeopleEvalOptions& o, std::FILE* out)
{
    if (o.model.empty())
        throw UsageError("give --model FILE (the .aam model, e.g. out/aam/imm-demo.aam)");
    if (o.persons < 2 || o.persons > kImmPersons)
        throw UsageError("--persons must be 2-40");
    if (o.enrolFrames < 1 || o.window < 1 || o.maxFits < 1 || o.maxFrames < 0)
        throw UsageError("--enrol-frames, --window and --max-fits must be >= 1, --max-frames >= 0");
    enrolTypes(o.enrol);
    const fs::path imm = o.imm.empty() ? fs::path(o.dataDir) / "imm_face_db" : fs::path(o.imm);
    const fs::path frames = o.frames.empty() ? fs::path(o.dataDir) / "fgnet_talking_face" / "images"
                                             : fs::path(o.frames);
    const bool withImm = o.imm != "none", withFgnet = o.frames != "none";
    PeopleEvalOptions withTruth = o;
    if (o.frames.empty() && o.truth.empty())
        withTruth.truth = (fs::path(o.dataDir) / "fgnet_talking_face" / "points").string();
    if (!withTruth.truth.empty() && withFgnet && !fs::is_directory(withTruth.truth))
        throw UsageError("--truth " + withTruth.truth + ": not a folder");
    if (withImm && !fs::is_directory(imm))
        throw UsageError("--imm " + imm.string() + ": not a folder");
    if (!o.stranger.empty() && !withFgnet)
        throw UsageError("--stranger needs the FGNet run (franck enrolled)");
    if (!o.stranger.empty() && !fs::is_directory(fs::path(o.stranger) / "frames"))
        throw UsageError("--stranger " + o.stranger + ": no frames folder (a facegen output)");
    if (withFgnet && !fs::is_directory(frames))
        throw UsageError("--frames " + frames.string() + ": not a folder");
    const vision::AamModelFile file = vision::loadAamModel(o.model);
    if (!file.ok)
        throw std::runtime_error(file.problem);
    vision::TrackedFaceFitterOptions fitterOptions;
    if (o.signatureResidual >= 0.f)
        fitterOptions.signatureMaxResidual = o.signatureResidual;
    if (o.textureGrid >= 0)
        fitterOptions.fit.textureGrid = o.textureGrid;
    if (o.nearest)
        fitterOptions.fit.appearanceSampling = vision::AamSampling::Nearest;
    vision::TrackedFaceFitter fitter(file.model, fitterOptions);
    BoxFinder boxes(o.cascade);
    vision::PersonGalleryOptions galleryOptions;
    if (o.acceptScore >= 0.f)
        galleryOptions.acceptScore = o.acceptScore;
    if (o.shapeWeight >= 0.f)
        galleryOptions.shapeWeight = o.shapeWeight;
    if (o.appearanceWeight >= 0.f)
        galleryOptions.appearanceWeight = o.appearanceWeight;
    if (o.textureWeight >= 0.f)
        galleryOptions.textureWeight = o.textureWeight;
    if (o.textureSpread > 0.f)
        galleryOptions.textureSpread = o.textureSpread;
    std::ofstream csvFile;
    std::ostream* csv = nullptr;
    if (!o.dump.empty()) {
        csvFile.open(o.dump);
        if (!csvFile)
            throw std::runtime_error(o.dump + ": cannot write");
        csv = &csvFile;
    }
    std::fprintf(out,
                 "model %s; boxes: Viola-Jones (%s) on the image shrunk by 2; signature: %d ok "
                 "fits after the shape units froze (at most %d fits of a still image); gallery: "
                 "shape weight %.2f, appearance weight %.2f, texture weight %.2f (spread %.1f), "
                 "acceptScore %.3f\n",
                 o.model.c_str(), o.cascade.c_str(), fitter.options().signatureFits, o.maxFits,
                 static_cast<double>(galleryOptions.shapeWeight),
                 static_cast<double>(galleryOptions.appearanceWeight),
                 static_cast<double>(galleryOptions.textureWeight),
                 static_cast<double>(galleryOptions.textureSpread),
                 static_cast<double>(galleryOptions.acceptScore));
    ImmResult immResult;
    vision::PersonGallery fgnetGallery(galleryOptions);
    if (withImm) {
        immResult = runImm(o, imm, boxes, fitter, galleryOptions, csv, out);
        // The IMM persons' type-1 signatures sit beside franck in the FGNet gallery.
        for (int person = 1; person <= std::min(o.persons, kImmPersons); ++person) {
            char name[32];
            for (const char sex : {'m', 'f'}) {
                std::snprintf(name, sizeof name, "%02d-1%c.jpg", person, sex);
                if (fs::exists(imm / name))
                    fgnetGallery.enrol(person, signatureOfStill(readGreyImage(imm / name), boxes,
                                                                fitter, o.maxFits));
            }
        }
        char name[32];
        std::snprintf(name, sizeof name, "01-1m.jpg");
        if (fs::exists(imm / name))
            timeRecognition(file.model, fitterOptions.fit, readGreyImage(imm / name), boxes,
                            fgnetGallery, out);
    }
    FgnetResult fgnetResult;
    if (withFgnet)
        fgnetResult = runFgnet(withTruth, frames, boxes, fitter, fgnetGallery, csv, out);
    if (!o.stranger.empty() && fgnetResult.ran) {
        const Rate notFranck = runStranger(o, o.stranger, fitter, fgnetGallery, out);
        std::fprintf(out, "people-stranger: not_franck=%s\n",
                     aam_report::number(notFranck.value(), "%.3f").c_str());
    }
    if (immResult.ran)
        std::fprintf(out, "people-heldout: rank1=%s rank1_turned=%s false_accept=%s\n",
                     aam_report::number(immResult.heldFrontal.value(), "%.3f").c_str(),
                     aam_report::number(immResult.heldTurned.value(), "%.3f").c_str(),
                     aam_report::number(immResult.heldFalseAccept.value(), "%.3f").c_str());
    std::fprintf(out, "people: rank1=%s rank1_turned=%s false_accept=%s fgnet_kept=%s\n",
                 aam_report::number(immResult.frontal.value(), "%.3f").c_str(),
                 aam_report::number(immResult.turned.value(), "%.3f").c_str(),
                 aam_report::number(immResult.falseAccept.value(), "%.3f").c_str(),
                 aam_report::number(fgnetResult.kept.value(), "%.3f").c_str());
    return 0;
}

}  // namespace

int runPeopleEval(const PeopleEvalOptions& options, std::FILE* out, std::FILE* err)
{
    try {
        return run(options, out);
    } catch (const UsageError& e) {
        std::fprintf(err, "mirror-eval people: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(err, "mirror-eval people: %s\n", e.what());
        return 1;
    }
}

}  // namespace mirror_eval
