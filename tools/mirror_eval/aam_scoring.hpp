#pragma once
// Scoring of fitted face points for `mirror-eval aam` (§5): every estimate and every truth is
// brought to CANDIDE-3 vertices (by CANDIDE's own numbers) through the annotation scheme tables
// of tools/aam (docs/aam-annotation-schemes.md), and compared on the vertices both have.
//
//  - NME of a frame: the mean distance over the compared points, over the truth's outer-eye-corner
//    distance (CANDIDE 20 and 53: IMM 13/21, FGNet 32/27, iBUG 45/36);
//  - point groups: the jaw line (CANDIDE 10, 30, 32, 63, 65), the brows (15-18, 48-51), and the
//    inner points, eyes, nose and lips: everything else the tables map;
//  - mouth opening: the inner lips' middles apart (CANDIDE 87 and 40), over the eye distance;
//  - Pearson's correlation of two series (jaw drop against the mouth opening).

#include "annotation_schemes.hpp"

#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

namespace mirror_eval {

/// Image positions by CANDIDE-3 vertex number.
using CandidePoints = std::map<int, Eigen::Vector2d>;

/// The points an annotation of `scheme` marks, as CANDIDE vertices (every row of the table).
/// Throws std::invalid_argument (one line) when the annotation has not the scheme's point count.
CandidePoints candidePointsOf(const aam::AnnotationScheme& scheme,
                              const std::vector<Eigen::Vector2d>& annotation);

/// A fitted mesh's vertices (mesh order) as CANDIDE vertices, by `candideNumber`.
CandidePoints candidePointsOf(const std::vector<int>& candideNumber,
                              const std::vector<Eigen::Vector2d>& vertices);

enum class PointGroup { Jaw, Brow, Inner };
PointGroup pointGroupOf(int candideNumber) noexcept;

/// Outer eye corner to outer eye corner (CANDIDE 20 to 53); nullopt when the truth lacks either.
std::optional<double> eyeCornerDistance(const CandidePoints& truth);

/// The mouth opening (CANDIDE 87 to 40) over the eye-corner distance; nullopt without them.
std::optional<double> mouthOpening(const CandidePoints& points, double eyeDistance);

struct FrameNme {
    double inner = 0;     ///< over the inner points
    double all = 0;       ///< over every compared point
    int innerPoints = 0;  ///< how many
    int allPoints = 0;
};

/// NME of `estimate` against `truth` over the vertices both have (and, when `only` is given, that
/// it has too), normalised by `eyeDistance` (the truth's eyeCornerDistance, taken before any
/// hidden truth point was left out); nullopt when there is no inner point to compare.
std::optional<FrameNme> frameNme(const CandidePoints& truth, const CandidePoints& estimate,
                                 double eyeDistance, const CandidePoints* only = nullptr);

/// Pearson's correlation of two equally long series; NaN when shorter than 2 or either is flat.
double pearson(const std::vector<double>& a, const std::vector<double>& b);

/// The FGNet-iBUG pairs of tools/aam (the dlib peer on FGNet truth without CANDIDE between), in
/// groups: the inner points (eyes, nose, lips: FGNet 27-67 but the brows), with the chin (FGNet
/// 7), every pair; and the inner points with the three centres FGNet marks and iBUG does not,
/// each the mean of an iBUG contour: the pupils (FGNet 31, 36: iBUG 36-41, 42-47) and the mouth
/// (FGNet 66: iBUG 60-67), alone and with the chin.
struct PairNme {
    double inner = 0, innerAndChin = 0, all = 0, withCentres = 0, withCentresAndChin = 0;
    int innerPoints = 0, innerAndChinPoints = 0, allPoints = 0, withCentresPoints = 0,
        withCentresAndChinPoints = 0;
};
PairNme fgnetIbugNme(const std::vector<Eigen::Vector2d>& fgnetTruth,
                     const std::vector<Eigen::Vector2d>& ibugEstimate);
/// The mean over frames of each group's NME (the counts of the first frame); zero when empty.
PairNme meanPairNme(const std::vector<PairNme>& frames);

}  // namespace mirror_eval
