#pragma once
// FixedCascade: an OpenCV Haar cascade converted to fixed point for FaceDetector (METHOD.md §3).
// Built once at start-up for one integral-table stride; evaluate() then decides one window in
// integer arithmetic, exactly as OpenCV's float evaluation decides it. It also keeps the row form
// of the same cascade (float thresholds, Q20 leaves) that RowPrefilter runs.

#include "vision/haar_cascade.hpp"

#include <cstdint>
#include <vector>

namespace vision {

/// A rectangle feature as integral-table offsets (for the cascade's table stride) and weights.
struct FixedFeature {
    std::int32_t ofs[3][4];
    std::int32_t weight[3];
    int rectCount;
};

/// A feature for the row prefilter: offsets in the plain table (step-1 scales), in the
/// column-deinterleaved one (step-2 scales) and in the one deinterleaved 4 ways (windows 4 px
/// apart: a coarse scan's), so the windows of a row are consecutive entries.
struct RowFeature {
    std::int32_t plain[3][4];
    std::int32_t split[3][4];
    std::int32_t split4[3][4];
    std::int32_t weight[3];
    bool twoRects;  ///< weight[2] == 0: most features; a kernel without the third rectangle
};

/// A stump of the row form: the file's float threshold, Q20 leaves.
struct RowStump {
    RowFeature feature;
    float threshold;
    std::int32_t left;
    std::int32_t right;
};

/// A two-node tree of the row form (alt2): node 0 leads to a leaf (`direct`) or to node 1
/// (leaves below1 and above1); node1OnBelow says which way.
struct RowTree {
    RowFeature feature0;
    RowFeature feature1;
    float threshold0;
    float threshold1;
    bool node1OnBelow;
    std::int32_t direct;
    std::int32_t below1;
    std::int32_t above1;
};

/// A stage: its threshold, its weak classifiers (first, count) and, for the row form, the Q20
/// bounds between which the exact path must decide.
struct FixedStage {
    std::int64_t threshold;  ///< Q40
    int first;               ///< first stump (stump cascades) or weak classifier (trees)
    int count;
    std::int32_t rowReject;  ///< a Q20 row sum below this: surely rejected
    std::int32_t rowPass;    ///< from this on: surely passed
};

/// A stump: node threshold Q48 (compared with feature * normalisation factor in Q48), leaves
/// Q40, and what the stage's later stumps can still add at most / least (early exits).
struct FixedStump {
    FixedFeature feature;
    std::int64_t threshold;
    std::int64_t left;
    std::int64_t right;
    std::int64_t restMax;
    std::int64_t restMin;
    int featureIndex;
    float fileThreshold;  ///< as in the file, for the row form
};

/// A node of a tree cascade; children as in HaarNode.
struct FixedNode {
    FixedFeature feature;
    std::int64_t threshold;  ///< Q48
    int left;
    int right;
    int featureIndex;
    float fileThreshold;
};

/// A tree: its nodes and leaves, and what the stage's later trees can still add.
struct FixedTree {
    int firstNode;
    int firstLeaf;
    std::int64_t restMax;
    std::int64_t restMin;
};

class FixedCascade {
public:
    /// Converts `cascade` for integral tables of `stride` entries per row. With `rowForm`,
    /// also builds the row form where the cascade allows one (rowForm()). Throws
    /// std::runtime_error on a cascade it cannot evaluate (empty, tilted features, non-integer
    /// rectangle weights, values out of the fixed-point range).
    FixedCascade(const HaarCascade& cascade, int stride, bool rowForm);

    /// OpenCV's variance normalisation factor of the window at `sum` / `sqsum` (its top-left
    /// entries), 0 when the window is flat.
    float windowNorm(const std::int32_t* sum, const std::uint32_t* sqsum) const noexcept;

    /// The window at `sum` / `sqsum`: 1 when it passes, -s when stage s rejects it, -1 also
    /// when it is flat. Stages before firstStage count as passed; with endStage >= 0, the
    /// stages from endStage on too (1: it passed stages firstStage..endStage-1).
    int evaluate(const std::int32_t* sum, const std::uint32_t* sqsum, int firstStage = 0,
                 int endStage = -1) const noexcept;

    int windowWidth() const noexcept { return winW_; }
    int windowHeight() const noexcept { return winH_; }
    bool stumps() const noexcept { return stumps_; }
    const std::vector<FixedStage>& stages() const noexcept { return stages_; }

    /// True when the row form exists: rowStumps() (stump cascades) or rowTrees() (two-node
    /// trees), parallel to the stages' weak classifiers.
    bool rowForm() const noexcept { return rowForm_; }
    const std::vector<RowStump>& rowStumps() const noexcept { return rowStumps_; }
    const std::vector<RowTree>& rowTrees() const noexcept { return rowTrees_; }

private:
    FixedFeature fixFeature(const HaarFeature& f) const;
    RowFeature rowFeature(const HaarFeature& f) const;
    void setNormalisation();
    bool fixFeatures(const HaarCascade& cascade, std::vector<FixedFeature>& out) const;
    void buildStages(const HaarCascade& cascade, const std::vector<FixedFeature>& features);
    void buildTrees(const HaarCascade& cascade, const std::vector<FixedFeature>& features);
    void sortTrees(const HaarCascade& cascade);
    void buildRowForm(const HaarCascade& cascade);
    int evaluateStumps(const std::int32_t* p, std::int64_t k, int firstStage,
                       int endStage) const noexcept;
    int evaluateTrees(const std::int32_t* p, std::int64_t k, int firstStage,
                      int endStage) const noexcept;

    int winW_ = 0;
    int winH_ = 0;
    int stride_ = 0;
    bool stumps_ = true;
    bool twoNodeTrees_ = false;  // every tree: node 0 -> (leaf | node 1), node 1 -> leaves
    std::vector<FixedStump> stumpList_;
    std::vector<FixedNode> nodes_;
    std::vector<std::int64_t> leaves_;
    std::vector<FixedTree> trees_;
    std::vector<FixedStage> stages_;
    std::int32_t normOfs_[4] = {};
    double normArea_ = 0.0;
    std::int64_t nfRejectBelow_ = 0;  // nf below this is surely flat (std dev <= 10)

    bool rowForm_ = false;
    std::vector<RowStump> rowStumps_;
    std::vector<RowTree> rowTrees_;
};

}  // namespace vision
