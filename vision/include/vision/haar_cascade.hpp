#pragma once
// HaarCascade: a Viola-Jones boosted cascade of Haar-like features as plain data (METHOD.md §3),
// read from OpenCV's cascade XML ("new" format, e.g. haarcascade_frontalface_default.xml and
// haarcascade_frontalface_alt2.xml of Debian's opencv-data) by a small reader written with the
// standard library only. Loaded once at start-up; FaceDetector converts it to fixed point.
//
// Values are kept exactly as written in the file (floats); OpenCV's own adjustments (the stage
// threshold lowered by 1e-5) are applied by the evaluator, not here.

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace vision {

/// One weighted rectangle of a feature, in window pixels.
struct HaarRect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;
    float weight = 0.0f;
};

/// A Haar-like feature: up to 3 weighted rectangles (unused ones have weight 0).
struct HaarFeature {
    std::array<HaarRect, 3> rects{};
    int rectCount = 0;
    bool tilted = false;  ///< 45-degree feature (parsed, not supported by FaceDetector)
};

/// An internal node of a weak classifier tree: feature value < threshold goes left. A child > 0
/// is a node index within the same tree; a child <= 0 is the leaf -child of the tree.
struct HaarNode {
    int featureIndex = 0;
    float threshold = 0.0f;
    int left = 0;
    int right = 0;
};

/// A weak classifier: nodeCount nodes from firstNode, nodeCount + 1 leaves from firstLeaf. A
/// stump (the default cascade) has one node and two leaves.
struct HaarWeakClassifier {
    int firstNode = 0;
    int nodeCount = 0;
    int firstLeaf = 0;
};

/// A stage: the sum of its weak classifiers' leaf values must reach `threshold`.
struct HaarStage {
    float threshold = 0.0f;
    int firstWeak = 0;
    int weakCount = 0;
};

struct HaarCascade {
    int windowWidth = 0;
    int windowHeight = 0;
    std::vector<HaarStage> stages;
    std::vector<HaarWeakClassifier> weak;
    std::vector<HaarNode> nodes;
    std::vector<float> leaves;
    std::vector<HaarFeature> features;

    /// True when every weak classifier is a single node (stump).
    bool stumpsOnly() const noexcept;
};

/// Reads a cascade file. Throws std::runtime_error with one line, e.g.
/// "cascade FILE: line N: expected <stages>", on a missing, truncated or wrong file.
HaarCascade loadHaarCascade(const std::string& path);

/// Parses cascade XML text; `name` is used in error messages in place of the file name.
HaarCascade parseHaarCascade(std::string_view text, const std::string& name);

}  // namespace vision
