// CandideMesh: vertex look-up and the linear deformation g = g0 + S sigma + A tau (§5).
#include "vision/candide_mesh.hpp"

#include <stdexcept>

namespace vision {

int CandideMesh::indexOfCandideVertex(int number) const noexcept
{
    for (std::size_t i = 0; i < candideNumber.size(); ++i) {
        if (candideNumber[i] == number)
            return static_cast<int>(i);
    }
    return -1;
}

namespace {

void addUnits(std::vector<Eigen::Vector3f>& vertices, const std::vector<CandideUnit>& units,
              const std::vector<float>& parameters, const char* what)
{
    if (parameters.size() != units.size()) {
        throw std::invalid_argument(std::string("deformedVertices: ") +
                                    std::to_string(parameters.size()) + " " + what +
                                    " parameters for " + std::to_string(units.size()) + " units");
    }
    for (std::size_t u = 0; u < units.size(); ++u) {
        const CandideUnit& unit = units[u];
        for (std::size_t k = 0; k < unit.vertices.size(); ++k) {
            vertices[static_cast<std::size_t>(unit.vertices[k])] +=
                parameters[u] * unit.displacements[k];
        }
    }
}

}  // namespace

std::vector<Eigen::Vector3f> deformedVertices(const CandideMesh& mesh,
                                              const std::vector<float>& sigma,
                                              const std::vector<float>& tau)
{
    std::vector<Eigen::Vector3f> vertices = mesh.vertices;
    addUnits(vertices, mesh.shapeUnits, sigma, "shape");
    addUnits(vertices, mesh.animationUnits, tau, "animation");
    return vertices;
}

const CandideUnit* findUnit(const std::vector<CandideUnit>& units, const std::string& name) noexcept
{
    for (const CandideUnit& unit : units) {
        const std::string stem = unit.name.substr(0, unit.name.find(" ("));
        if (stem == name)
            return &unit;
    }
    return nullptr;
}

}  // namespace vision
