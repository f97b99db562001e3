#pragma once
// mirror-eval people: who a face is (§6; dissertation 6.2), through the path the appliance runs:
// the face tracker's Viola-Jones detector (its cascade, on the image shrunk by 2) gives the box,
// vision::TrackedFaceFitter fits the still image frame after frame until the face's signature
// settles (shape units frozen, then signatureFits ok fits), vision::PersonGallery matches it.
//  - IMM (40 persons, 6 photographs each): each person enrolled from --enrol types (1, or 1 and
//    2), probed with the others: rank-1 accuracy per type (frontal: 1, 2, 5; turned: 3, 4;
//    "joker" 6 apart), for the persons the demo model was built from and the 10 it left out
//    (04, 08, ... 40: the honest figure) apart; then the gallery with half the persons (odd,
//    then even) and every probe of the others: how many are accepted as someone (false accept).
//  - FGNet's talking face (--frames DIR [--truth DIR], or the data folder's): franck enrolled from
//  frames
//    [0, --enrol-frames), then the rest cut into windows of --window frames, each a new track
//    whose settled signature must be accepted as franck (IMM's persons enrolled beside him);
//    with --stranger DIR (a facegen folder) its moving face, someone else, through the same
//    windows from facegen's truth boxes: never to be taken for franck.
// Also the cost: the appearance parameters (what recognition adds to a collecting face's frame)
// and one match, timed. Final line
//   `people: rank1=.. rank1_turned=.. false_accept=.. fgnet_kept=..`
// over all 40 persons (rank-1 over the frontal probe types, turned: 3 and 4).

#include <cstdio>
#include <string>

namespace mirror_eval {

struct PeopleEvalOptions {
    std::string model;  ///< the .aam model file
    std::string dataDir = "../shared/data";
    std::string imm;     ///< default: DATA/imm_face_db ("none": skip)
    std::string frames;  ///< default: DATA/fgnet_talking_face/images ("none": skip)
    /// Per-frame .pts beside the frames' names: the face whose box holds their centre is the
    /// sequence's person (default with the default frames: DATA/fgnet_talking_face/points;
    /// without: the largest face).
    std::string truth;
    std::string cascade = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";
    std::string stranger;      ///< a facegen folder: its moving face must not be taken for franck
    std::string enrol = "1";   ///< IMM types enrolled: "1" or "1,2"
    int persons = 40;          ///< IMM: only persons 1..N (a quick run)
    int enrolFrames = 100;     ///< FGNet: franck's enrolment frames
    int window = 100;          ///< FGNet: frames per recognition track
    int maxFrames = 0;         ///< FGNet: only the first N frames (0: all)
    int maxFits = 30;          ///< fits of one still image before its signature must have settled
    float acceptScore = -1.f;  ///< < 0: the gallery's default
    float shapeWeight = -1.f, appearanceWeight = -1.f;  ///< < 0: the gallery's default
    float textureWeight = -1.f, textureSpread = -1.f;   ///< < 0: the gallery's default
    float signatureResidual =
        -1.f;               ///< TrackedFaceFitterOptions::signatureMaxResidual (< 0: default)
    int textureGrid = -1;   ///< the texture descriptor's cells per side (< 0: the fitter's default)
    bool nearest = false;   ///< appearance parameters from the nearest pixel, not bilinear
    bool perImage = false;  ///< say why an IMM photograph has no signature
    std::string dump;       ///< write every signature to this CSV (for measuring distances)
};

/// Runs, prints the report and its final line to `out`. Returns 0; 2 for bad arguments and 1 for
/// unreadable data, each with one line on `err`.
int runPeopleEval(const PeopleEvalOptions& options, std::FILE* out, std::FILE* err);

}  // namespace mirror_eval
