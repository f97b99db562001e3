#include "face_match.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

namespace mirror_eval {

namespace {

/// Greedy one-to-one pairing over candidate scores, best (lowest `cost`) first; ties by index.
Pairing greedy(std::size_t candidates, std::size_t truths,
               std::vector<std::tuple<float, int, int>> pairs)
{
    std::sort(pairs.begin(), pairs.end());
    Pairing p;
    p.truthOfCandidate.assign(candidates, -1);
    p.candidateOfTruth.assign(truths, -1);
    for (const auto& [cost, c, t] : pairs) {
        (void)cost;
        if (p.truthOfCandidate[static_cast<std::size_t>(c)] >= 0 ||
            p.candidateOfTruth[static_cast<std::size_t>(t)] >= 0)
            continue;
        p.truthOfCandidate[static_cast<std::size_t>(c)] = t;
        p.candidateOfTruth[static_cast<std::size_t>(t)] = c;
        ++p.matches;
    }
    return p;
}

}  // namespace

BoxF toBoxF(const vision::Rect& r) noexcept
{
    return {static_cast<float>(r.x), static_cast<float>(r.y), static_cast<float>(r.width),
            static_cast<float>(r.height)};
}

BoxF squareAbout(vision::Point2f centre, float size) noexcept
{
    return {centre.x - 0.5f * size, centre.y - 0.5f * size, size, size};
}

BoxF boundingBox(std::span<const vision::Point2f> points) noexcept
{
    if (points.empty())
        return {};
    float x0 = points[0].x, x1 = points[0].x, y0 = points[0].y, y1 = points[0].y;
    for (const auto& p : points) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    return {x0, y0, x1 - x0, y1 - y0};
}

float iou(const BoxF& a, const BoxF& b) noexcept
{
    const float w = std::min(a.x + a.width, b.x + b.width) - std::max(a.x, b.x);
    const float h = std::min(a.y + a.height, b.y + b.height) - std::max(a.y, b.y);
    if (w <= 0.f || h <= 0.f)
        return 0.f;
    const float inter = w * h;
    const float uni = a.width * a.height + b.width * b.height - inter;
    return uni > 0.f ? inter / uni : 0.f;
}

bool wholeInFrame(const BoxF& b, vision::Size frame) noexcept
{
    return b.x >= 0.f && b.y >= 0.f && b.x + b.width <= static_cast<float>(frame.width) &&
           b.y + b.height <= static_cast<float>(frame.height);
}

BoxF partInView(const BoxF& b, vision::Size frame) noexcept
{
    const float x0 = std::max(b.x, 0.f);
    const float y0 = std::max(b.y, 0.f);
    const float x1 = std::min(b.x + b.width, static_cast<float>(frame.width));
    const float y1 = std::min(b.y + b.height, static_cast<float>(frame.height));
    return {x0, y0, std::max(0.f, x1 - x0), std::max(0.f, y1 - y0)};
}

bool contains(const BoxF& box, vision::Point2f p) noexcept
{
    return p.x >= box.x && p.x <= box.x + box.width && p.y >= box.y && p.y <= box.y + box.height;
}

BoxF landmarkConventionBox(vision::Point2f centre, float side, float rollDegrees) noexcept
{
    // Positive roll is clockwise on screen (y down): the face's down direction is (-sin, cos).
    const float r = rollDegrees * 3.14159265358979323846f / 180.f;
    const float drop = kLandmarkBoxDrop * side;
    return squareAbout({centre.x - drop * std::sin(r), centre.y + drop * std::cos(r)},
                       kLandmarkBoxPerSide * side);
}

bool detectionMatchesFace(const vision::Rect& box, const LandmarkFace& face) noexcept
{
    const BoxF b = toBoxF(box);
    if (!contains(b, face.leftEye) || !contains(b, face.rightEye) || !contains(b, face.mouthCentre))
        return false;
    const float scale = kBoxPerEyeMouth * face.eyeMouthDistance();
    const float side = 0.5f * (b.width + b.height);
    return side >= scale / kScaleTolerance && side <= scale * kScaleTolerance;
}

std::string detectRuleText()
{
    char text[256];
    std::snprintf(text, sizeof text,
                  "correct = box contains both eyes and the mouth centre, and its side is within "
                  "x%.0f of %.1f x eye-mouth distance; one detection per face, closest first",
                  static_cast<double>(kScaleTolerance), static_cast<double>(kBoxPerEyeMouth));
    return text;
}

std::string landmarkBoxText()
{
    char text[320];
    std::snprintf(text, sizeof text,
                  "the landmark box of our square face box: a square of %.3f x its side centred "
                  "%.3f x its side lower along the roll (measured on dlib's 68-point example "
                  "faces: a Viola-Jones square runs forehead to below the mouth, the landmarks "
                  "eyebrows to chin)",
                  static_cast<double>(kLandmarkBoxPerSide), static_cast<double>(kLandmarkBoxDrop));
    return text;
}

Pairing pairDetections(std::span<const vision::Rect> boxes,
                       std::span<const LandmarkFace* const> faces)
{
    std::vector<std::tuple<float, int, int>> pairs;
    for (std::size_t c = 0; c < boxes.size(); ++c) {
        const vision::Rect& b = boxes[c];
        const float bx = static_cast<float>(b.x) + 0.5f * static_cast<float>(b.width);
        const float by = static_cast<float>(b.y) + 0.5f * static_cast<float>(b.height);
        for (std::size_t t = 0; t < faces.size(); ++t) {
            if (!detectionMatchesFace(b, *faces[t]))
                continue;
            const vision::Point2f fc = faces[t]->centre();
            pairs.emplace_back(std::hypot(bx - fc.x, by - fc.y), static_cast<int>(c),
                               static_cast<int>(t));
        }
    }
    return greedy(boxes.size(), faces.size(), std::move(pairs));
}

Pairing pairByIou(std::span<const BoxF> candidates, std::span<const BoxF> truths, float minIou)
{
    std::vector<std::tuple<float, int, int>> pairs;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
        for (std::size_t t = 0; t < truths.size(); ++t) {
            const float v = iou(candidates[c], truths[t]);
            if (v >= minIou)
                pairs.emplace_back(-v, static_cast<int>(c), static_cast<int>(t));
        }
    }
    return greedy(candidates.size(), truths.size(), std::move(pairs));
}

}  // namespace mirror_eval
