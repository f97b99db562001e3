#pragma once
// Annotation schemes mapped onto CANDIDE-3 vertices (§5, dissertation 5.3.1: the marked points of
// each training image fit CANDIDE), one table per scheme, and the table between the FGNet and
// iBUG schemes (the dlib peer answers in iBUG order, the FGNet truth is in Cootes' own).
//
// A table row says: CANDIDE-3 vertex N lies at the mean of one or two of the scheme's points.
// "Left" is the person's left (image right for a face looking at the camera); CANDIDE's +x.
// A scheme point without a row has no CANDIDE counterpart (pupil centres: CANDIDE has only the
// iris' bounding box; points between two vertices). The tables, and why each row is what it is,
// are in docs/aam-annotation-schemes.md; the drawings they were checked on come from
// `aam-build draw --scheme`.

#include "annotation_files.hpp"
#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <span>
#include <string_view>
#include <vector>

namespace aam {

/// The mean of one or two annotation points (the second -1 when one).
struct PointMean {
    std::array<int, 2> points{-1, -1};

    int count() const noexcept { return points[1] < 0 ? 1 : 2; }
    Eigen::Vector2d of(const std::vector<Eigen::Vector2d>& annotation) const;
};

struct SchemeRow {
    int candideVertex;  ///< CANDIDE-3's number (vision::CandideMesh::candideNumber)
    PointMean at;
};

struct AnnotationScheme {
    std::string_view name;
    int pointCount;
    std::span<const SchemeRow> rows;
};

const AnnotationScheme& immScheme();    ///< IMM face database, 58 points (.asf)
const AnnotationScheme& fgnetScheme();  ///< FGNet talking face, Cootes' 68 points (.pts)
const AnnotationScheme& ibugScheme();   ///< iBUG / 300-W 68 points (.pts: menpo, dlib)

/// The scheme named "imm", "fgnet" or "ibug"; throws std::invalid_argument otherwise.
const AnnotationScheme& schemeNamed(std::string_view name);

/// One CANDIDE vertex (index into the mesh) and where the annotation puts it.
struct MarkedPoint {
    int vertex;
    Eigen::Vector2d image;
};

/// The annotation's points that `face` has a vertex for, through the scheme's table. Throws
/// AnnotationError when the annotation has not the scheme's number of points.
std::vector<MarkedPoint> markedPoints(const AnnotationScheme& scheme, const Annotation& annotation,
                                      const vision::CandideMesh& face);

/// A point both the FGNet and the iBUG markup have, each as a mean of its own points.
struct FgnetIbugPair {
    PointMean fgnet;
    PointMean ibug;
};
std::span<const FgnetIbugPair> fgnetIbugPairs();

}  // namespace aam
