// The dissertation's cut of CANDIDE-3 (§5, dissertation 5.3.1), and the eye openings the 2D warp
// needs: steps in reduceCandideForTracking.
#include "vision/candide_reduction.hpp"

#include <algorithm>
#include <stdexcept>

namespace vision {

namespace {

float eyebrowTop(const CandideMesh& full)
{
    float top = -1e30f;
    for (int number : kCandideEyebrowVertices) {
        const int i = full.indexOfCandideVertex(number);
        if (i < 0)
            throw std::runtime_error("CANDIDE mesh: eyebrow vertex " + std::to_string(number) +
                                     " missing");
        top = std::max(top, full.vertices[static_cast<std::size_t>(i)].y());
    }
    return top;
}

int indexOf(const CandideMesh& full, int number)
{
    const int i = full.indexOfCandideVertex(number);
    if (i < 0)
        throw std::runtime_error("CANDIDE mesh: vertex " + std::to_string(number) + " missing");
    return i;
}

bool usesIris(const CandideMesh& full, const std::array<int, 3>& t)
{
    return std::any_of(t.begin(), t.end(), [&](int v) {
        const int number = full.candideNumber[static_cast<std::size_t>(v)];
        return std::find(kCandideIrisVertices.begin(), kCandideIrisVertices.end(), number) !=
               kCandideIrisVertices.end();
    });
}

/// A strip across the opening: corner, then alternately upper and lower lid, then the corner.
void addEyeOpening(const CandideMesh& full, const EyeOpening& eye,
                   std::vector<std::array<int, 3>>& out)
{
    const auto u = [&](int k) { return indexOf(full, eye.upper[static_cast<std::size_t>(k)]); };
    const auto l = [&](int k) { return indexOf(full, eye.lower[static_cast<std::size_t>(k)]); };
    out.push_back({indexOf(full, eye.outerCorner), u(0), l(0)});
    for (int k = 0; k < 2; ++k) {
        out.push_back({u(k), l(k), l(k + 1)});
        out.push_back({u(k), u(k + 1), l(k + 1)});
    }
    out.push_back({u(2), l(2), indexOf(full, eye.innerCorner)});
}

/// Triangles with no vertex above the eyebrows, the eyeball surfaces replaced by the openings.
std::vector<std::array<int, 3>> faceTriangles(const CandideMesh& full)
{
    const float top = eyebrowTop(full);
    std::vector<std::array<int, 3>> kept;
    for (const auto& t : full.triangles) {
        const bool below = std::all_of(t.begin(), t.end(), [&](int v) {
            return full.vertices[static_cast<std::size_t>(v)].y() <= top;
        });
        if (below && !usesIris(full, t))
            kept.push_back(t);
    }
    for (const EyeOpening& eye : kCandideEyeOpenings)
        addEyeOpening(full, eye, kept);
    return kept;
}

/// A unit restricted to the kept vertices, its indices renumbered.
CandideUnit remapped(const CandideUnit& unit, const std::vector<int>& newIndex)
{
    CandideUnit out{unit.name, unit.label, {}, {}};
    for (std::size_t k = 0; k < unit.vertices.size(); ++k) {
        const int to = newIndex[static_cast<std::size_t>(unit.vertices[k])];
        if (to < 0)
            continue;
        out.vertices.push_back(to);
        out.displacements.push_back(unit.displacements[k]);
    }
    return out;
}

const CandideUnit& animationUnit(const CandideMesh& full, const KeptUnit& kept)
{
    for (const CandideUnit& unit : full.animationUnits) {
        if (unit.label == kept.label && unit.name.starts_with(kept.name))
            return unit;
    }
    throw std::runtime_error("CANDIDE mesh: no animation unit " + std::string(kept.label) + " (" +
                             std::string(kept.name) + ")");
}

const CandideUnit& shapeUnit(const CandideMesh& full, std::string_view name)
{
    const CandideUnit* unit = findUnit(full.shapeUnits, std::string(name));
    if (unit == nullptr)
        throw std::runtime_error("CANDIDE mesh: no shape unit \"" + std::string(name) + "\"");
    return *unit;
}

}  // namespace

CandideMesh reduceCandideForTracking(const CandideMesh& full)
{
    const auto triangles = faceTriangles(full);
    std::vector<bool> used(full.vertices.size(), false);
    for (const auto& t : triangles) {
        for (int v : t)
            used[static_cast<std::size_t>(v)] = true;
    }

    CandideMesh face;
    std::vector<int> newIndex(full.vertices.size(), -1);
    for (std::size_t v = 0; v < full.vertices.size(); ++v) {
        if (!used[v])
            continue;
        newIndex[v] = static_cast<int>(face.vertices.size());
        face.vertices.push_back(full.vertices[v]);
        face.candideNumber.push_back(full.candideNumber[v]);
    }
    for (const auto& t : triangles) {
        face.triangles.push_back({newIndex[static_cast<std::size_t>(t[0])],
                                  newIndex[static_cast<std::size_t>(t[1])],
                                  newIndex[static_cast<std::size_t>(t[2])]});
    }
    for (const KeptUnit& kept : kTrackedAnimationUnits) {
        face.animationUnits.push_back(remapped(animationUnit(full, kept), newIndex));
    }
    for (std::string_view name : kTrackedShapeUnits) {
        face.shapeUnits.push_back(remapped(shapeUnit(full, name), newIndex));
    }
    return face;
}

}  // namespace vision
