#pragma once
// The points `aam-annotate --points FILE` places instead of clicks (scripted annotation, tests):
// one "x y" per line in image pixels, in the scheme's order; '#' comments and blank lines skipped.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace annotate {

/// Throws std::runtime_error (one line, "PATH:LINE: why") on a line that is not two finite
/// numbers, or when the file cannot be read.
std::vector<Eigen::Vector2d> readPointList(const std::string& path);

}  // namespace annotate
