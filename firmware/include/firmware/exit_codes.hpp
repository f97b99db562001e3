#pragma once
// Process exit codes of `mirror`, documented in `mirror --help` and the README.

namespace firmware {

inline constexpr int kExitOk =
    0;  ///< ran and stopped as asked (frames done, quit, signal, end of file)
inline constexpr int kExitInternal = 1;  ///< an unexpected internal error
inline constexpr int kExitConfig = 2;    ///< bad command line or config: nothing was started
inline constexpr int kExitSource = 3;    ///< the frame source could not be opened
inline constexpr int kExitDisplay = 4;   ///< the display could not be opened
inline constexpr int kExitPipeline = 5;  ///< the vision pipeline or renderer could not be set up

}  // namespace firmware
