#pragma once
// The HOG boxes of an annotated run, kept in a file (`mirror-eval aam --boxes FILE`): the HOG
// detector takes most of a run's time (35 of FGNet's 45 seconds here), and its boxes do not
// change with our fit. A text file, one line a frame: `<frame stem> <left> <top> <right>
// <bottom>`, or `<frame stem> -` for a frame without a box on the truth face (stems without
// spaces). A run detects only the frames the file lacks, and adds them to it. Frames are known
// by their stem alone: one file per sequence and --upsample.

#include "head_fit_runner.hpp"

#include <map>
#include <optional>
#include <string>

namespace mirror_eval {

class BoxCache {
public:
    /// Reads `path` when it exists (a malformed line: std::runtime_error naming the line); an
    /// empty path keeps nothing.
    explicit BoxCache(std::string path);

    /// The kept answer for `stem`: none when the file lacks it, else the box or its absence.
    std::optional<std::optional<FaceBoxPx>> find(const std::string& stem) const;
    void put(const std::string& stem, const std::optional<FaceBoxPx>& box);
    /// Writes the file when anything was put (to a temporary file, then renamed over it).
    void save() const;

private:
    std::string path_;
    std::map<std::string, std::optional<FaceBoxPx>> boxes_;
    bool changed_ = false;
};

}  // namespace mirror_eval
