#pragma once
// Writes one cardgen sequence to a folder: frame_00000.png ..., truth.csv and scenario.txt.

#include "scenarios.hpp"

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace cardgen {

struct GenerateOptions {
    std::string scenario;
    std::string outDir;  ///< created if missing; old frame_*.png in it are removed first
    int frames = kDefaultFrames;
    std::uint32_t seed = 1;
    cv::Size size{720, 480};                 ///< the issue's benchmark size
    std::string dataDir = "../shared/data";  ///< the shared real data (relative to the cwd)
    std::string background;  ///< overrides the scenario's backgrounds when not empty
};

struct GeneratedSequence {
    std::string dir;
    std::string background;  ///< the photograph used
    int frames = 0;
    int framesWithoutCard = 0;  ///< truth rows with empty corner fields
};

/// The photograph for a scenario: `override` when given, else the first readable candidate.
/// Throws std::runtime_error naming what was tried when none can be read.
std::string resolveBackground(const ScenarioInfo& info, const std::string& dataDir,
                              const std::string& override);
/// The same over an explicit candidate list (Scenario::backgrounds()).
std::string resolveBackground(const std::string& scenario,
                              const std::vector<std::string>& candidates,
                              const std::string& dataDir, const std::string& override);

/// One truth.csv row: "frame,x0,y0,x1,y1,x2,y2,x3,y3" (3 decimals), or "frame,,,,,,,," when the
/// frame has no card in view.
std::string truthRow(int frame, const FrameSpec& spec);

/// Renders and writes the whole sequence. Throws std::runtime_error with one line on failure.
GeneratedSequence generateSequence(const GenerateOptions& options);

}  // namespace cardgen
