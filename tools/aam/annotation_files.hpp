#pragma once
// Landmark files the AAM's training images come with (§5, dissertation 5.3.1: points marked on
// each image fit CANDIDE):
//  - IMM .asf ("AAM Shape File", Stegmann's format): a point count, then one line per point
//    "<path#> <type> <x rel.> <y rel.> <point#> <connects from> <connects to>" with coordinates
//    relative to the image size (some files append three more numbers per point, ignored), and
//    the host image's file name;
//  - .pts (FGNet talking face, menpo, dlib's output): "version: 1", "n_points: N", "{", N lines
//    "x y" in pixels, "}".
// '#' comment lines and blank lines are skipped. Any problem is an AnnotationError whose what() is
// one line, "PATH:LINE: what was wrong".

#include <Eigen/Core>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace aam {

class AnnotationError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The points of one annotated image, in pixels (x right, y down).
struct Annotation {
    std::vector<Eigen::Vector2d> points;
    std::string hostImage;  ///< the image file the .asf names (empty for .pts)
};

/// The IMM face database's image size: its .asf coordinates are fractions of it.
inline constexpr int kImmImageWidth = 640;
inline constexpr int kImmImageHeight = 480;

Annotation readAsf(std::istream& in, const std::string& name, int imageWidth = kImmImageWidth,
                   int imageHeight = kImmImageHeight);
Annotation loadAsf(const std::string& path, int imageWidth = kImmImageWidth,
                   int imageHeight = kImmImageHeight);

Annotation readPts(std::istream& in, const std::string& name);
Annotation loadPts(const std::string& path);

/// An .asf file by loadAsf, any other by loadPts.
Annotation loadAnnotation(const std::string& path);

/// Writes `points` as a .pts file (for integrators' own annotations and for tests).
void writePts(std::ostream& out, const std::vector<Eigen::Vector2d>& points);

}  // namespace aam
