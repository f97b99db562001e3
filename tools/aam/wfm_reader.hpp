#pragma once
// Reads a CANDIDE .wfm face definition (the format of Ahlberg's CANDIDE-3 report, LiTH-ISY-R-2326)
// into vision::CandideMesh. Offline and at model building only: the runtime gets its mesh from the
// model file, so the vision core needs no parser.
//
// The format: '#' comment lines and blank lines anywhere; then, in order, a vertex count and one
// "x y z" line per vertex; a triangle count and one "i j k" line each; an animation unit count
// and per unit a count and "vertex dx dy dz" lines; the same for the shape units; animation and
// shape parameters (a count and "unit value" lines); texture (a count; only 0 is supported); the
// global motion (rotation, scale, translation: three "x y z" lines). A unit's name is the first
// comment line before its count ("# AUV11 Jaw drop (AU26/27)", "# FAP 3 open_jaw", "# Head
// height"). Any problem is a WfmError whose what() is one line, "PATH:LINE: what was wrong".

#include "vision/candide_mesh.hpp"

#include <istream>
#include <stdexcept>
#include <string>

namespace aam {

class WfmError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Parses a .wfm from `in`; `name` is the file name errors start with.
vision::CandideMesh readWfm(std::istream& in, const std::string& name);
/// Opens and parses the file at `path` (an unreadable file is a WfmError too).
vision::CandideMesh loadWfm(const std::string& path);

}  // namespace aam
