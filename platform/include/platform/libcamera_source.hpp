#pragma once
// LibcameraSource: frames from a camera through libcamera (the appliance's camera path).

#include "platform/frame_source.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace platform {

struct LibcameraOptions {
    std::string camera = "0";  ///< an index into libcamera's list, or an id as `cam -l` prints it
    int width = 640;
    int height = 480;
    double fps = 30.0;  ///< asked by FrameDurationLimits where the camera has it; 0 = default
    std::vector<vision::PixelFormat> formats;  ///< best first (empty: defaultFormatPreference())
    int bufferCount = 4;  ///< frame buffers (and requests) shared with the camera; at least 2
    std::int64_t timeoutNs = 2'000'000'000;  ///< no frame within this: next() is Lost ("stalled")
    std::int64_t firstFrameTimeoutNs = 5'000'000'000;  ///< for the first frame (sensor start-up)
};

/// \class LibcameraSource
/// One stream (the VideoRecording role, the Viewfinder role where that is missing) of one camera,
/// with the API that libcamera 0.0.3 (Debian 12) and the later 0.x releases share, as rpicam-apps
/// uses it: CameraManager, Camera::acquire/configure/start, FrameBufferAllocator, requests reused
/// with Request::ReuseBuffers, the requestCompleted signal, controls::SensorTimestamp.
///
/// The constructor starts a CameraManager, picks the camera, configures the stream at the
/// requested size (libcamera may adjust it: size() says what was granted) in the first format of
/// `formats` the camera offers, allocates the buffers, maps every dmabuf once, creates one request
/// per buffer, starts the camera and queues them all. It throws std::runtime_error with one line
/// ("libcamera: camera 0: ...") when any step fails. Only one CameraManager may exist in a process:
/// destroy a source before opening the next.
///
/// Completed requests travel from libcamera's thread to next() through a fixed ring (one slot per
/// request) under a mutex; next() waits on a condition variable with a timeout. The delivered frame
/// is a view into the mapped buffer of the newest completed request, which stays with us until the
/// following next(): then it is reused and queued again. Older completed requests waiting behind it
/// are queued again at once (latest frame wins, no queue builds up). The timestamp is the sensor's
/// (controls::SensorTimestamp, CLOCK_MONOTONIC ns), else the buffer's.
///
/// next() returns Lost, with lastError() set, when the camera is unplugged (its `disconnected`
/// signal), when no frame arrives within the timeout, or when a request cannot be queued. Then the
/// source stays Lost: destroy it and open a new one (ReconnectingSource does that). next() never
/// throws; our code in it never allocates, but libcamera does, about 5 times per frame inside
/// Request::reuse() and Camera::queueRequest() (measured under vimc).
///
/// Unplugging: libcamera's hot-unplug event may come late or never, but a request it cannot
/// queue to the vanished device ("No such device") turns Cancelled at once: next() checks its
/// requests' status every 100 ms while waiting and returns Lost ("camera gone") when one is.
/// libcamera 0.0.3 then cannot release that camera (stopping it is a fatal assertion, destroying
/// it running a std::terminate), so the destructor parks its libcamera objects for the rest of
/// the process, and since one process may hold only one CameraManager, later LibcameraSource
/// constructors throw and libcameraRestartRequired() turns true: the firmware should exit and
/// let systemd start it again (the new process opens the camera when it is back). A camera that
/// stalls while present is stopped and released normally.
class LibcameraSource final : public FrameSource {
public:
    explicit LibcameraSource(const LibcameraOptions& options);
    ~LibcameraSource() override;

    /// E.g. "libcamera:platform/vimc.0 Sensor B (640x480 RGB24)".
    const char* description() const noexcept override;
    vision::Size size() const noexcept override;
    vision::PixelFormat format() const noexcept override;
    SourceStatus next(vision::Frame& frame) noexcept override;
    std::int64_t lastWaitNs() const noexcept override;
    const char* lastError() const noexcept override;
    /// libcameraRestartRequired().
    bool needsProcessRestart() const noexcept override;

    /// Frames the camera completed with an error status (skipped), since construction.
    std::uint64_t failedFrames() const noexcept;
    /// Completed frames dropped because a newer one was already waiting.
    std::uint64_t droppedFrames() const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// True once a camera vanished while running: this process cannot open cameras any more (see
/// LibcameraSource); restarting the process recovers.
bool libcameraRestartRequired() noexcept;

/// True when libcamera lists at least one camera. Starts and stops a CameraManager, so call it
/// before opening a LibcameraSource, never while one exists.
bool libcameraCameraAvailable() noexcept;

}  // namespace platform
