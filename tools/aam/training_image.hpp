#pragma once
// The training photographs of §5 (dissertation 5.3.1: each marked image is warped to the mean
// shape): found from their annotation files and read as grey images, through readBoundedFile
// (limits::kImageFileBytes) and OpenCV's decoder. The appearance model is grey, as the text's.

#include "annotation_files.hpp"

#include <opencv2/core.hpp>
#include <string>

namespace aam {

/// The image an annotation file annotates: the .asf's host image beside it, else the file with
/// its extension replaced by .jpg or .png (in the same folder, or in ../images for FGNet's
/// points/ folder). Throws std::runtime_error (one line) when there is none.
std::string annotatedImagePath(const std::string& annotationPath, const Annotation& annotation);

/// The image at `path` as 8-bit grey; throws std::runtime_error (one line naming the path).
cv::Mat loadGreyImage(const std::string& path);

/// The person a file shows, for the leave-persons-out split: its name up to the first '-' or '_'
/// ("01" for IMM's ".../01-1m.asf", "franck" for FGNet's "franck_00000.pts"), else the whole stem.
std::string personOf(const std::string& path);

}  // namespace aam
