#pragma once
// Where colorlab samples the recording: a sample list file (`name x y [radius]`) or an automatic
// grid, checked against the frame size before any frame is measured.

#include <stdexcept>
#include <string>
#include <vector>

namespace colorlab {

inline constexpr int kDefaultRadius = 3;

/// One sampled point: the mean colour over the disc of `radius` pixels around (x, y).
struct Sample {
    std::string name;
    int x = 0;
    int y = 0;
    int radius = kDefaultRadius;
    std::string origin;  ///< "FILE:LINE" for error messages, or "grid"
};

/// A problem with the sample list (unreadable, malformed, empty, outside the frame): one line,
/// "FILE:LINE: what" where a line is known. colorlab exits 2 on it.
class SampleError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Reads `path`: one sample a line, `name x y [radius]`, '#' starts a comment, blank lines are
/// ignored. Names must be unique and made of letters, digits, '-', '_' and '.' (they become file
/// names). Throws SampleError.
std::vector<Sample> readSampleFile(const std::string& path);

/// Parses "NxM" (columns x rows, each 1..64). Throws SampleError.
void parseGrid(const std::string& spec, int& columns, int& rows);

/// columns x rows samples at the centres of equal cells of a width x height frame, named
/// "r<row>c<col>".
std::vector<Sample> gridSamples(int width, int height, int columns, int rows, int radius);

/// Throws SampleError when there are no samples or a sample's disc does not lie inside the
/// frame: "samples.txt:3: sample 'skin' at (900, 20) is outside the 720x576 frame".
void checkSamples(const std::vector<Sample>& samples, int width, int height);

}  // namespace colorlab
