#pragma once
// Per frame, per sample: the mean R, G, B over the sample's disc of a BGR24 frame.

#include "samples.hpp"
#include "vision/image.hpp"

#include <vector>

namespace colorlab {

/// Mean colour of one sample in one frame (0..255, fractional).
struct Measurement {
    double r = 0.0;
    double g = 0.0;
    double b = 0.0;
    bool saturated = false;  ///< some pixel of the disc has a channel at 255 (clipped)
};

/// Mean over the pixels with dx^2 + dy^2 <= radius^2 around the sample (the disc must lie inside
/// the frame: see checkSamples). `frame` is BGR24.
Measurement measureDisc(const vision::ConstImageView& frame, const Sample& sample) noexcept;

/// Everything measured in a recording: one row of measurements (one per sample) per frame.
struct Recording {
    std::vector<Sample> samples;
    std::vector<long> frameNumbers;                      ///< source frame index of each row
    std::vector<std::vector<Measurement>> measurements;  ///< [row][sample]
    int width = 0;
    int height = 0;

    /// True when any sample of the row is saturated.
    bool rowSaturated(std::size_t row) const noexcept;
};

}  // namespace colorlab
