#pragma once
// A head's texture: one IMM photograph and where each CANDIDE vertex lies in it, from the
// photograph's 5.3.1 fit (§5; aam::fitCandide on its marked points through the IMM table). The
// person's shape units come with it, so a rendered head has that person's proportions.

#include "vision/candide_mesh.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace headgen {

struct HeadTexture {
    std::string name;                 ///< the .asf's stem, e.g. "04-1m"
    cv::Mat photo;                    ///< 8-bit BGR
    std::vector<Eigen::Vector2d> uv;  ///< each mesh vertex in `photo`, pixels (the frontal fit)
    std::vector<float> sigma;         ///< the person's shape units
    cv::Scalar skin;                  ///< mean BGR over the cheeks (for the hand)
};

/// Fits `mesh` to the IMM annotation at `asfPath` and reads its photograph. Throws
/// std::runtime_error (one line naming the file) when either cannot be read.
HeadTexture loadHeadTexture(const vision::CandideMesh& mesh, const std::string& asfPath);

/// Whether the IMM file at `path` shows a person the demo model leaves out (scripts/dev model
/// holds back persons 04, 08, ... 40).
bool heldOutOfDemoModel(const std::string& path);

/// The IMM persons the demo model leaves out (scripts/dev model holds back every fourth of the
/// 40): their frontal neutral photographs (type 1), so a model built as the demo's never saw the
/// rendered face. Paths under `immDir`, sorted.
std::vector<std::string> heldOutImmFaces(const std::string& immDir);

}  // namespace headgen
