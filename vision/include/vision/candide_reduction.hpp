#pragma once
// The dissertation's cut of CANDIDE-3 for face tracking (§5; dissertation 5.3.1):
//  - the vertices above the eyebrows and the triangles that use them dropped (hair and hats
//    there; the face area Cootes et al. and Matthews & Baker model), and with them the vertices no
//    kept triangle uses (CANDIDE-3's "not used" duplicates 4, 35-39, 41-43);
//  - beyond the text, for the 2D warp, which needs triangles that tile the face without overlap:
//    CANDIDE-3.1.4's eyeball and pupil surfaces (through the iris box vertices 67-74) overlap the
//    eyelids in the frontal view, so they are replaced by a strip of six triangles across each
//    eye opening between its corners and lid vertices; the iris vertices are then unused;
//  - the six animation units of Dornaika & Ahlberg for the mouth and brows;
//  - ten of the fourteen shape units. The text says only that four were "eliminated where
//    insufficient information was available in the 2D image"; ours are the two depth-only units
//    (a frontal image says nothing of depth), Head height (what remains of it below the brows is
//    the chin's drop, which a single image cannot tell from Jaw drop with Mouth vertical position)
//    and Nose pointing up (the nose tip alone; the IMM markup, our many-person set, has no tip).

#include "vision/candide_mesh.hpp"

#include <array>
#include <string_view>

namespace vision {

/// CANDIDE-3's eyebrow vertices (its Appendix A: 15-18 left, 48-51 right); a vertex higher than
/// all of them is above the eyebrows.
inline constexpr std::array<int, 8> kCandideEyebrowVertices{15, 16, 17, 18, 48, 49, 50, 51};

/// CANDIDE-3's iris bounding-box vertices (its appendix A: 67, 68, 71, 72 left; 69, 70, 73, 74
/// right), the corners of the eyeball surfaces.
inline constexpr std::array<int, 8> kCandideIrisVertices{67, 68, 69, 70, 71, 72, 73, 74};

/// One eye opening's contour in CANDIDE-3 numbers: the outer corner, the upper lid's lash line
/// (outer edge, centre, inner edge), the lower lid's lash line (the same), the inner corner.
struct EyeOpening {
    int outerCorner;
    std::array<int, 3> upper;
    std::array<int, 3> lower;
    int innerCorner;
};
inline constexpr std::array<EyeOpening, 2> kCandideEyeOpenings{{
    {20, {97, 21, 105}, {99, 22, 107}, 23},   // left
    {53, {98, 54, 106}, {100, 55, 108}, 56},  // right
}};

/// The kept animation units in the order of their parameters: label and name in the .wfm.
struct KeptUnit {
    std::string_view label;
    std::string_view name;
};
inline constexpr std::array<KeptUnit, 6> kTrackedAnimationUnits{{
    {"AUV11", "Jaw drop"},
    {"AUV2", "Lip stretcher"},
    {"AUV3", "Brow lowerer"},
    {"AUV5", "Outer brow raiser"},
    {"AUV0", "Upper lip raiser"},
    {"AUV14", "Lip corner depressor"},
}};
/// The kept shape units in the order of their parameters (see the file comment for the four left).
inline constexpr std::array<std::string_view, 10> kTrackedShapeUnits{"Eyebrows vertical position",
                                                                     "Eyes vertical position",
                                                                     "Eyes, width",
                                                                     "Eyes, height",
                                                                     "Eye separation distance",
                                                                     "Nose vertical position",
                                                                     "Mouth vertical position",
                                                                     "Mouth width",
                                                                     "Eyes vertical difference",
                                                                     "Chin width"};
inline constexpr std::array<std::string_view, 4> kDroppedShapeUnits{
    "Head height", "Cheeks z", "Nose z-extension", "Nose, pointing up"};

/// The face mesh the AAM tracks, cut from the full CANDIDE-3 as above. Its `candideNumber` keeps
/// each vertex's CANDIDE-3 number. Throws std::runtime_error (one line) when a kept unit is
/// missing.
CandideMesh reduceCandideForTracking(const CandideMesh& full);

}  // namespace vision
