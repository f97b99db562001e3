#pragma once
// ReconnectingSource: keeps a camera-like source alive across "missing at boot", "unplugged" and
// "stalled" by closing it and opening it again with back-off.

#include "platform/frame_pacer.hpp"
#include "platform/frame_source.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace platform {

/// Where a ReconnectingSource stands with its camera.
enum class CameraState : std::uint8_t {
    Running,   ///< frames flow from the camera
    Lost,      ///< the camera failed (or was missing at start); the first retry is pending
    Retrying,  ///< at least one reopen failed; retrying with growing back-off
};

/// "running", "lost", "retrying".
const char* cameraStateName(CameraState state) noexcept;

struct ReconnectOptions {
    std::int64_t firstRetryNs = 500'000'000;  ///< delay before the first reopen after a failure
    std::int64_t maxRetryNs = 8'000'000'000;  ///< doubled after each failed reopen, up to this
    bool (*processRestartRequired)() noexcept = nullptr;  ///< needsProcessRestart(); null: false
};

/// Opens the inner source; throws std::runtime_error with one line when it cannot.
using SourceOpener = std::function<std::unique_ptr<FrameSource>()>;

/// \class ReconnectingSource
/// Wraps a device source (LibcameraSource, V4l2Source) built by `open`. The constructor tries to
/// open it once and does not throw when that fails: the mirror starts without its camera and keeps
/// trying. A failure of the inner source (next() returning Lost: unplugged, stalled past its
/// timeout, a driver error) destroys it at once, so its buffers, mappings and file descriptors are
/// released before anything is opened again; each later next() call returns Lost immediately
/// (no blocking, no allocation) until the retry is due, then opens a new inner source on the
/// calling thread. Retries wait firstRetryNs, then twice as long after each failure, up to
/// maxRetryNs; a successful reopen resets the delay.
///
/// Size and format are fixed at construction: those of the inner source when it opened then, else
/// `expectedSize` / `expectedFormat` (what the config asks for). A camera opened later that
/// delivers anything else (e.g. missing at boot, and the camera adjusts 640x480 to 636x480) is
/// closed again and counted as a failed attempt; needsPipelineRebuild() and lastError() say so, and
/// rebuilding the pipeline with a new source adopts it.
///
/// State changes (state(), transitions()) let the firmware log each change once and draw its
/// "camera unavailable" screen while the state is not Running. Sequence numbers continue across
/// reconnects. The inner source's stall timeout is what detects a stalled camera: next() returns
/// within that timeout.
class ReconnectingSource final : public FrameSource {
public:
    /// `name` is the spec for messages, e.g. "libcamera:0".
    ReconnectingSource(std::string name, SourceOpener open, vision::Size expectedSize,
                       vision::PixelFormat expectedFormat, ReconnectOptions options = {},
                       PacerClock& clock = monotonicPacerClock());
    ~ReconnectingSource() override;

    /// The inner source's description while running, else e.g. "libcamera:0 (unavailable)".
    const char* description() const noexcept override;
    vision::Size size() const noexcept override { return size_; }
    vision::PixelFormat format() const noexcept override { return format_; }
    SourceStatus next(vision::Frame& frame) noexcept override;
    std::int64_t lastWaitNs() const noexcept override { return lastWaitNs_; }
    /// Why the camera is not running (the inner failure or the last reopen's error); "" running.
    const char* lastError() const noexcept override { return error_; }

    CameraState state() const noexcept { return state_; }
    /// Counts state changes since construction (Running -> Lost -> Retrying -> Running ...): the
    /// firmware logs when it differs from the value it saw last.
    std::uint64_t transitions() const noexcept { return transitions_; }
    /// Delay before the next reopen (valid while not Running).
    std::int64_t retryDelayNs() const noexcept { return delayNs_; }
    /// Reopen attempts that failed since the camera was last running.
    int failedAttempts() const noexcept { return failedAttempts_; }
    /// Successful reopens after the first open.
    std::uint64_t reconnects() const noexcept { return reconnects_; }
    /// Whether an inner source is open now.
    bool connected() const noexcept { return inner_ != nullptr; }
    /// True while the camera is there but delivers another size or format than the mirror runs
    /// (e.g. missing at boot, and the camera adjusts the configured size): the firmware should
    /// rebuild its pipeline with a new source. Cleared by a successful reopen.
    bool needsPipelineRebuild() const noexcept override { return needsRebuild_; }
    /// Whether the kind of source `open` makes can never be opened again in this process:
    /// ReconnectOptions::processRestartRequired (for libcamera libcameraRestartRequired), false
    /// without one.
    bool needsProcessRestart() const noexcept override
    {
        return options_.processRestartRequired != nullptr && options_.processRestartRequired();
    }

private:
    bool tryOpen() noexcept;
    void setState(CameraState state) noexcept;
    void failed(const char* why) noexcept;

    std::string name_;
    SourceOpener open_;
    ReconnectOptions options_;
    PacerClock* clock_;
    std::unique_ptr<FrameSource> inner_;
    bool everOpened_ = false;
    bool needsRebuild_ = false;
    bool sizeFixed_ = false;
    vision::Size size_;
    vision::PixelFormat format_;
    CameraState state_ = CameraState::Lost;
    std::uint64_t transitions_ = 0;
    std::int64_t delayNs_ = 0;
    std::int64_t nextAttemptNs_ = 0;
    int failedAttempts_ = 0;
    std::uint64_t reconnects_ = 0;
    std::uint64_t sequence_ = 0;
    std::int64_t lastWaitNs_ = 0;
    char unavailable_[256] = {};
    char error_[512] = {};
};

}  // namespace platform
