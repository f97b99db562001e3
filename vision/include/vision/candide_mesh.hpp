#pragma once
// CandideMesh: the CANDIDE-3 generic face (Ahlberg 2001) as plain data, the 3D model the AAM
// constrains its 2D shape with (§5). Built at start-up or offline (read from a .wfm by the tools'
// reader, or from the model file); nothing here runs per frame.
//
// Model frame (CANDIDE's own): x towards the person's left (image right for a face looking at the
// camera), y up, z out of the face towards the camera; units of about half a face width.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace vision {

/// A linear deformation of the mesh: an animation unit (expression) or a shape unit (the person's
/// own proportions). Mathematically the same (§5): vertex += parameter * displacement.
struct CandideUnit {
    std::string name;  ///< as the file names it, e.g. "Jaw drop (AU26/27)"
    std::string
        label;  ///< "AUV11" for an action unit vector, "FAP 3" for a FAP, "" for a shape unit
    std::vector<int> vertices;                   ///< indices into CandideMesh::vertices
    std::vector<Eigen::Vector3f> displacements;  ///< one per entry of `vertices`
};

struct CandideMesh {
    std::vector<Eigen::Vector3f> vertices;  ///< base shape, model frame
    std::vector<int> candideNumber;         ///< CANDIDE-3's number of each vertex (tables use it)
    std::vector<std::array<int, 3>> triangles;  ///< indices into `vertices`
    std::vector<CandideUnit> animationUnits;
    std::vector<CandideUnit> shapeUnits;

    /// Index into `vertices` of the vertex CANDIDE-3 numbers `number`, or -1 when it was dropped.
    int indexOfCandideVertex(int number) const noexcept;
};

/// The base shape moved by shape parameters sigma (one per shape unit) and animation parameters
/// tau (one per animation unit): g = g0 + S sigma + A tau, Ahlberg's eq. (1).
std::vector<Eigen::Vector3f> deformedVertices(const CandideMesh& mesh,
                                              const std::vector<float>& sigma,
                                              const std::vector<float>& tau);

/// The unit named `name` (compared up to its first " (", so "Jaw drop" finds "Jaw drop (AU26/27)"),
/// or nullptr.
const CandideUnit* findUnit(const std::vector<CandideUnit>& units,
                            const std::string& name) noexcept;

}  // namespace vision
