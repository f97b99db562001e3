// The scheme tables (see docs/aam-annotation-schemes.md for each row's reason) and the mapping of
// an annotation onto the face mesh's vertices.
#include "annotation_schemes.hpp"

#include <stdexcept>
#include <string>

namespace aam {

namespace {

// IMM 58 points: jaw 0-12 from the image's left; eyes 13-20 (left eye) and 21-28 (right), each
// from its outer corner over the upper lid; brows 29-33 (left, inner to outer, upper edge only)
// and 34-38 (right); mouth 39-46 (right corner, upper lip, left corner, lower lip; 41 on the
// lips' meeting line); nose 47-57 (down the right side of the bridge, round the nostrils, up).
constexpr SchemeRow kImmRows[] = {
    {63, {{2, -1}}},  {65, {{5, -1}}},   {10, {{6, -1}}},  {32, {{7, -1}}},
    {30, {{10, -1}}},                                                         // jaw
    {20, {{13, -1}}}, {21, {{15, -1}}},  {23, {{17, -1}}}, {22, {{19, -1}}},  // left eye
    {53, {{21, -1}}}, {54, {{23, -1}}},  {56, {{25, -1}}}, {55, {{27, -1}}},  // right eye
    {17, {{29, -1}}}, {16, {{31, -1}}},  {15, {{33, -1}}},                    // left brow
    {50, {{34, -1}}}, {49, {{36, -1}}},  {48, {{38, -1}}},                    // right brow
    {64, {{39, -1}}}, {66, {{40, -1}}},  {87, {{41, -1}}}, {33, {{42, -1}}},
    {31, {{43, -1}}}, {85, {{44, -1}}},  {8, {{45, -1}}},  {86, {{46, -1}}},  // mouth
    {59, {{50, -1}}}, {112, {{51, -1}}}, {6, {{52, -1}}},  {111, {{53, -1}}},
    {26, {{54, -1}}},  // nose
};

// FGNet talking face, Cootes' 68 points: jaw 0-14 from the image's left; brows 15-20 (left) and
// 21-26 (right) as closed loops from the outer end over the top; eyes 27-30 (right) and 32-35
// (left) from the outer corner over the upper lid, their pupils at 31 and 36; nose 37-47 with its
// tip at 67; outer lips 48-59 from the right corner over the upper lip; inner lips 60-62 the lower
// lip from the right, 63-65 the upper lip from the left, the mouth's centre 66 (read off frames 0
// and 300: 60 and 65, 62 and 63 are pairs at the inner corners, so a corner is their mean).
constexpr SchemeRow kFgnetRows[] = {
    {63, {{3, -1}}},   {65, {{6, -1}}},  {10, {{7, -1}}},  {32, {{8, -1}}},
    {30, {{11, -1}}},                                                         // jaw
    {15, {{15, -1}}},  {16, {{16, -1}}}, {17, {{18, -1}}}, {18, {{20, -1}}},  // left brow
    {48, {{21, -1}}},  {49, {{22, -1}}}, {50, {{24, -1}}}, {51, {{26, -1}}},  // right brow
    {53, {{27, -1}}},  {54, {{28, -1}}}, {56, {{29, -1}}}, {55, {{30, -1}}},  // right eye
    {20, {{32, -1}}},  {21, {{33, -1}}}, {23, {{34, -1}}}, {22, {{35, -1}}},  // left eye
    {59, {{40, -1}}},  {6, {{41, -1}}},  {26, {{42, -1}}}, {112, {{46, -1}}},
    {111, {{47, -1}}}, {5, {{67, -1}}},  // nose
    {64, {{48, -1}}},  {80, {{49, -1}}}, {66, {{50, -1}}}, {7, {{51, -1}}},
    {33, {{52, -1}}},  {79, {{53, -1}}}, {31, {{54, -1}}}, {85, {{56, -1}}},
    {8, {{57, -1}}},   {86, {{58, -1}}},                                      // outer lips
    {89, {{60, 65}}},  {40, {{61, -1}}}, {88, {{62, 63}}}, {87, {{64, -1}}},  // inner lips
};

// iBUG / 300-W 68 points: jaw 0-16 from the image's left; brows 17-21 (right, outer to inner)
// and 22-26 (left, inner to outer); nose bridge 27-30 (30 the tip), nostrils 31-35; eyes 36-41
// (right) and 42-47 (left), from the corner on the image's left over the upper lid; outer lips
// 48-59 and inner lips 60-67, from the right corner over the upper lip.
constexpr SchemeRow kIbugRows[] = {
    {63, {{5, -1}}},   {65, {{7, -1}}},  {10, {{8, -1}}},   {32, {{9, -1}}},
    {30, {{11, -1}}},                                       // jaw
    {48, {{17, -1}}},  {49, {{18, 19}}}, {50, {{21, -1}}},  // right brow
    {17, {{22, -1}}},  {16, {{24, 25}}}, {15, {{26, -1}}},  // left brow
    {5, {{30, -1}}},   {59, {{31, -1}}}, {112, {{32, -1}}}, {6, {{33, -1}}},
    {111, {{34, -1}}}, {26, {{35, -1}}},                                       // nose
    {53, {{36, -1}}},  {54, {{37, 38}}}, {56, {{39, -1}}},  {55, {{40, 41}}},  // right eye
    {23, {{42, -1}}},  {21, {{43, 44}}}, {20, {{45, -1}}},  {22, {{46, 47}}},  // left eye
    {64, {{48, -1}}},  {80, {{49, -1}}}, {66, {{50, -1}}},  {7, {{51, -1}}},
    {33, {{52, -1}}},  {79, {{53, -1}}}, {31, {{54, -1}}},  {85, {{56, -1}}},
    {8, {{57, -1}}},   {86, {{58, -1}}},                                       // outer lips
    {89, {{60, -1}}},  {87, {{62, -1}}}, {88, {{64, -1}}},  {40, {{66, -1}}},  // inner lips
};

constexpr AnnotationScheme kImm{"imm", 58, kImmRows};
constexpr AnnotationScheme kFgnet{"fgnet", 68, kFgnetRows};
constexpr AnnotationScheme kIbug{"ibug", 68, kIbugRows};

// FGNet point(s) : iBUG point(s) at the same place on the face.
constexpr FgnetIbugPair kFgnetIbug[] = {
    {{{0, -1}}, {{0, -1}}},   {{{1, -1}}, {{2, -1}}},   {{{3, -1}}, {{5, -1}}},
    {{{6, -1}}, {{7, -1}}},   {{{7, -1}}, {{8, -1}}},   {{{8, -1}}, {{9, -1}}},
    {{{11, -1}}, {{11, -1}}}, {{{13, -1}}, {{14, -1}}}, {{{14, -1}}, {{16, -1}}},  // jaw
    {{{21, -1}}, {{17, -1}}}, {{{22, -1}}, {{18, 19}}}, {{{24, -1}}, {{21, -1}}},  // right brow
    {{{18, -1}}, {{22, -1}}}, {{{16, -1}}, {{24, 25}}}, {{{15, -1}}, {{26, -1}}},  // left brow
    {{{67, -1}}, {{30, -1}}}, {{{40, -1}}, {{31, -1}}}, {{{46, -1}}, {{32, -1}}},
    {{{41, -1}}, {{33, -1}}}, {{{47, -1}}, {{34, -1}}}, {{{42, -1}}, {{35, -1}}},  // nose
    {{{27, -1}}, {{36, -1}}}, {{{28, -1}}, {{37, 38}}}, {{{29, -1}}, {{39, -1}}},
    {{{30, -1}}, {{40, 41}}}, {{{34, -1}}, {{42, -1}}}, {{{33, -1}}, {{43, 44}}},
    {{{32, -1}}, {{45, -1}}}, {{{35, -1}}, {{46, 47}}},  // eyes
    {{{48, -1}}, {{48, -1}}}, {{{49, -1}}, {{49, -1}}}, {{{50, -1}}, {{50, -1}}},
    {{{51, -1}}, {{51, -1}}}, {{{52, -1}}, {{52, -1}}}, {{{53, -1}}, {{53, -1}}},
    {{{54, -1}}, {{54, -1}}}, {{{55, -1}}, {{55, -1}}}, {{{56, -1}}, {{56, -1}}},
    {{{57, -1}}, {{57, -1}}}, {{{58, -1}}, {{58, -1}}}, {{{59, -1}}, {{59, -1}}},  // outer lips
    {{{60, 65}}, {{60, -1}}}, {{{64, -1}}, {{62, -1}}}, {{{62, 63}}, {{64, -1}}},
    {{{61, -1}}, {{66, -1}}},  // inner lips
};

}  // namespace

Eigen::Vector2d PointMean::of(const std::vector<Eigen::Vector2d>& annotation) const
{
    const Eigen::Vector2d first = annotation.at(static_cast<std::size_t>(points[0]));
    if (points[1] < 0)
        return first;
    return 0.5 * (first + annotation.at(static_cast<std::size_t>(points[1])));
}

const AnnotationScheme& immScheme()
{
    return kImm;
}
const AnnotationScheme& fgnetScheme()
{
    return kFgnet;
}
const AnnotationScheme& ibugScheme()
{
    return kIbug;
}

const AnnotationScheme& schemeNamed(std::string_view name)
{
    for (const AnnotationScheme* s : {&kImm, &kFgnet, &kIbug}) {
        if (s->name == name)
            return *s;
    }
    throw std::invalid_argument("unknown annotation scheme \"" + std::string(name) +
                                "\" (imm, fgnet or ibug)");
}

std::vector<MarkedPoint> markedPoints(const AnnotationScheme& scheme, const Annotation& annotation,
                                      const vision::CandideMesh& face)
{
    if (static_cast<int>(annotation.points.size()) != scheme.pointCount) {
        throw AnnotationError(std::string(scheme.name) +
                              " annotation: " + std::to_string(annotation.points.size()) +
                              " points, the scheme has " + std::to_string(scheme.pointCount));
    }
    std::vector<MarkedPoint> marked;
    for (const SchemeRow& row : scheme.rows) {
        const int vertex = face.indexOfCandideVertex(row.candideVertex);
        if (vertex >= 0)
            marked.push_back({vertex, row.at.of(annotation.points)});
    }
    return marked;
}

std::span<const FgnetIbugPair> fgnetIbugPairs()
{
    return kFgnetIbug;
}

}  // namespace aam
