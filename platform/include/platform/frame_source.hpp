#pragma once
// FrameSource: where camera frames come from (synthetic scene, file replay, later libcamera/V4L2).

#include "vision/image.hpp"

#include <cstdint>

namespace platform {

enum class SourceStatus {
    Ok,           ///< a new frame was delivered
    EndOfStream,  ///< a finite source (file without looping) has no more frames
    Lost,         ///< the device failed; lastError() says why; the caller may retry later
};

/// A camera-like producer of frames. Opened (and its buffers allocated) in the constructor, which
/// throws with a one-line reason on failure. next() never throws and never allocates.
class FrameSource {
public:
    virtual ~FrameSource() = default;
    FrameSource() = default;
    FrameSource(const FrameSource&) = delete;
    FrameSource& operator=(const FrameSource&) = delete;

    /// What this source is, for status and logs, e.g. "file:/path/video.avi (720x528 BGR24)".
    virtual const char* description() const noexcept = 0;
    /// Size and format of every delivered frame; fixed after construction.
    virtual vision::Size size() const noexcept = 0;
    virtual vision::PixelFormat format() const noexcept = 0;
    /// Waits until the next frame is due (the source's pacing) and delivers it. The view in
    /// `frame` stays valid until the next call.
    virtual SourceStatus next(vision::Frame& frame) noexcept = 0;
    /// How long the last next() spent idle, waiting for the frame to be due (pacing) or to arrive
    /// (a camera), as opposed to working on it. The loop reports the two apart.
    virtual std::int64_t lastWaitNs() const noexcept { return 0; }
    /// Reason for the last Lost status; empty when none.
    virtual const char* lastError() const noexcept { return ""; }
    /// True while the device is back but delivers another size or format than size() and
    /// format(): the firmware should rebuild its pipeline with a new source.
    virtual bool needsPipelineRebuild() const noexcept { return false; }
    /// True once no frame can come again in this process (libcamera 0.0.3 after its camera
    /// vanished while running): the firmware should end the process, without running static
    /// destructors, and let the service manager start a new one.
    virtual bool needsProcessRestart() const noexcept { return false; }
};

}  // namespace platform
