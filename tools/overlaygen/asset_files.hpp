#pragma once
// The files overlaygen owns in assets/overlays/: per model <name>/<name>.obj and .mtl, and the
// generated block of catalogue.toml.

#include "model.hpp"

#include <string>
#include <vector>

namespace overlaygen {

struct GeneratedFile {
    std::string path;  ///< relative to the overlay directory
    std::string text;
};

/// The OBJ and MTL files of the models (not the catalogue).
std::vector<GeneratedFile> meshFiles(const std::vector<Model>& models);

/// Writes the mesh files and merges the generated block into `dir`/catalogue.toml. Throws
/// std::runtime_error naming the file when one cannot be written.
void writeAssets(const std::string& dir, const std::vector<Model>& models);

/// Files in `dir` that differ from what the generator makes now (missing ones included), each
/// as "path: why". Empty when the committed assets are up to date.
std::vector<std::string> staleAssets(const std::string& dir, const std::vector<Model>& models);

/// Whole file as text; empty string when it cannot be read.
std::string readText(const std::string& path);

}  // namespace overlaygen
