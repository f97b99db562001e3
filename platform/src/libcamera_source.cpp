#include "platform/libcamera_source.hpp"

#include "platform/camera_formats.hpp"

#include <libcamera/libcamera.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

namespace platform {

namespace {

std::int64_t monotonicNs() noexcept
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

/// libcamera writes INFO and WARN lines to stderr by default, and its logSetLevel() takes exact
/// category names only (no "*"). The appliance's log is ours and every failure reaches it as a
/// one-line error, so libcamera's own log is off unless LIBCAMERA_LOG_LEVELS or
/// LIBCAMERA_LOG_FILE asks for it (field debugging).
void quietLibcameraLogs() noexcept
{
    if (std::getenv("LIBCAMERA_LOG_LEVELS") == nullptr &&
        std::getenv("LIBCAMERA_LOG_FILE") == nullptr)
        libcamera::logSetTarget(libcamera::LoggingTargetNone);
}

bool allDigits(const std::string& s)
{
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

struct Mapping {
    void* address = MAP_FAILED;
    std::size_t length = 0;
};

/// Where one buffer's pixels are in our address space.
struct MappedBuffer {
    const std::uint8_t* plane0 = nullptr;
    const std::uint8_t* plane1 = nullptr;  ///< NV12 chroma, or nullptr
};

}  // namespace

/// The libcamera objects of a camera that vanished while running (see Impl::park()).
struct ParkedCamera {
    std::unique_ptr<libcamera::CameraManager> manager;
    std::shared_ptr<libcamera::Camera> camera;
    std::unique_ptr<libcamera::CameraConfiguration> config;
    std::unique_ptr<libcamera::FrameBufferAllocator> allocator;
    std::vector<std::unique_ptr<libcamera::Request>> requests;
};

std::atomic<bool>& restartRequired() noexcept
{
    static std::atomic<bool> required{false};
    return required;
}

/// How often next() looks for requests cancelled by a vanished device while it waits.
constexpr std::int64_t kGoneCheckNs = 100'000'000;

struct LibcameraSource::Impl {
    std::string name;  ///< "camera 0" in errors
    std::unique_ptr<libcamera::CameraManager> manager;
    std::shared_ptr<libcamera::Camera> camera;
    bool acquired = false;
    bool started = false;
    std::unique_ptr<libcamera::CameraConfiguration> config;
    libcamera::Stream* stream = nullptr;
    std::unique_ptr<libcamera::FrameBufferAllocator> allocator;
    std::vector<std::unique_ptr<libcamera::Request>> requests;
    std::vector<MappedBuffer> buffers;  ///< by request cookie
    std::vector<Mapping> mappings;
    libcamera::ControlList startControls;

    vision::Size size;
    vision::PixelFormat format = vision::PixelFormat::RGB24;
    int stride = 0;
    std::int64_t timeoutNs = 0;
    std::int64_t firstFrameTimeoutNs = 0;

    // Filled by libcamera's thread, drained by next().
    std::mutex mutex;
    std::condition_variable arrived;
    std::vector<libcamera::Request*> ring;  ///< capacity = number of requests; never grows
    std::size_t ringHead = 0;
    std::size_t ringCount = 0;
    bool disconnected = false;
    bool deviceGone = false;  ///< a request was cancelled while running (anyRequestCancelled)

    libcamera::Request* held = nullptr;  ///< the request whose buffer the caller is viewing
    bool lost = false;
    std::uint64_t sequence = 0;
    std::uint64_t failed = 0;
    std::uint64_t dropped = 0;
    std::int64_t lastWaitNs = 0;
    std::string description;
    char error[256] = {};

    [[noreturn]] void fail(const std::string& what) const
    {
        throw std::runtime_error("libcamera: " + name + ": " + what);
    }

    void open(const LibcameraOptions& options);
    void selectCamera(const std::string& which);
    void configure(const LibcameraOptions& options);
    void allocateAndMap();
    void start(double fps);
    void close() noexcept;

    void requestComplete(libcamera::Request* request);
    void onDisconnected();
    bool requeue(libcamera::Request* request) noexcept;
    bool anyRequestCancelled() const noexcept;
    void park() noexcept;
    SourceStatus next(vision::Frame& frame) noexcept;
    SourceStatus lose(const char* why) noexcept;
};

void LibcameraSource::Impl::open(const LibcameraOptions& options)
{
    name = allDigits(options.camera) ? "camera " + options.camera : options.camera;
    if (options.width < 16 || options.height < 16 || options.width > 16384 ||
        options.height > 16384)
        fail("invalid size " + std::to_string(options.width) + "x" +
             std::to_string(options.height));
    if (options.bufferCount < 2 || options.bufferCount > 32)
        fail("buffer count must be 2..32, not " + std::to_string(options.bufferCount));
    timeoutNs = options.timeoutNs > 0 ? options.timeoutNs : 2'000'000'000;
    // The first frame may take longer: sensor start-up, and emulated machines are slow.
    firstFrameTimeoutNs = std::max(options.firstFrameTimeoutNs, timeoutNs);

    if (restartRequired().load())
        fail(
            "a camera vanished while running and libcamera 0.0.3 cannot release it: restart the "
            "mirror to open cameras again");
    quietLibcameraLogs();
    manager = std::make_unique<libcamera::CameraManager>();
    if (const int ret = manager->start(); ret < 0)
        fail(std::string("cannot start the camera manager: ") + std::strerror(-ret));
    selectCamera(options.camera);
    configure(options);
    allocateAndMap();
    start(options.fps);

    char formatText[16];
    description = "libcamera:" + camera->id() + " (" + std::to_string(size.width) + "x" +
                  std::to_string(size.height) + " " + vision::pixelFormatName(format) + " " +
                  fourccName(libcameraFourccFor(format), formatText, sizeof formatText) + ")";
}

// `which` is an index into libcamera's list ("0", "1", ...) or a camera id as `cam -l` prints it
// (e.g. "platform/vimc.0 Sensor B").
void LibcameraSource::Impl::selectCamera(const std::string& which)
{
    const std::vector<std::shared_ptr<libcamera::Camera>> cameras = manager->cameras();
    if (cameras.empty())
        fail("no camera found (is the sensor connected and its driver loaded?)");
    if (allDigits(which)) {
        const unsigned long index = std::strtoul(which.c_str(), nullptr, 10);
        if (which.size() > 4 || index >= cameras.size())
            fail("no such camera (" + std::to_string(cameras.size()) + " found, index from 0)");
        camera = cameras[index];
    } else {
        camera = manager->get(which);
        if (!camera) {
            std::string ids;
            for (const auto& c : cameras)
                ids += (ids.empty() ? "" : ", ") + c->id();
            fail("no camera with this id (found: " + ids + ")");
        }
    }
    if (const int ret = camera->acquire(); ret < 0)
        fail("cannot acquire the camera (" + std::string(std::strerror(-ret)) +
             "; is another program using it?)");
    acquired = true;
    camera->disconnected.connect(this, &Impl::onDisconnected);
}

void LibcameraSource::Impl::configure(const LibcameraOptions& options)
{
    // A vector converts to both 0.0.3's StreamRoles and the Span later releases take.
    for (const libcamera::StreamRole role :
         {libcamera::StreamRole::VideoRecording, libcamera::StreamRole::Viewfinder}) {
        const std::vector<libcamera::StreamRole> roles{role};
        config = camera->generateConfiguration(roles);
        if (config && config->size() == 1)
            break;
    }
    if (!config || config->size() != 1)
        fail("cannot generate a video or viewfinder configuration");

    libcamera::StreamConfiguration& streamConfig = config->at(0);
    std::vector<std::uint32_t> offered;
    for (const libcamera::PixelFormat& f : streamConfig.formats().pixelformats())
        offered.push_back(f.fourcc());
    const std::vector<vision::PixelFormat> preference =
        options.formats.empty() ? defaultFormatPreference() : options.formats;
    const std::optional<vision::PixelFormat> chosen = chooseLibcameraFormat(offered, preference);
    if (!chosen) {
        std::string list;
        char text[16];
        for (const std::uint32_t code : offered)
            list += std::string(list.empty() ? "" : " ") + fourccName(code, text, sizeof text);
        fail("offers none of the formats we take (offered: " + list + ")");
    }

    streamConfig.pixelFormat = libcamera::PixelFormat(libcameraFourccFor(*chosen));
    streamConfig.size = libcamera::Size(static_cast<unsigned>(options.width),
                                        static_cast<unsigned>(options.height));
    streamConfig.bufferCount = static_cast<unsigned>(options.bufferCount);
    if (config->validate() == libcamera::CameraConfiguration::Invalid)
        fail("configuration " + streamConfig.toString() + " is invalid");
    // validate() may adjust the size (to what the pipeline can scale to) and the buffer count; a
    // changed format is one we did not ask for.
    const std::optional<vision::PixelFormat> granted =
        pixelFormatFromLibcamera(streamConfig.pixelFormat.fourcc());
    if (!granted)
        fail("camera adjusted the format to " + streamConfig.pixelFormat.toString() +
             ", which we do not take");
    if (const int ret = camera->configure(config.get()); ret < 0)
        fail("cannot configure " + streamConfig.toString() + ": " + std::strerror(-ret));

    format = *granted;
    size = {static_cast<int>(streamConfig.size.width), static_cast<int>(streamConfig.size.height)};
    stride = static_cast<int>(streamConfig.stride);
    stream = streamConfig.stream();
    if (stride < size.width * vision::bytesPerPixel(format))
        fail("stride " + std::to_string(stride) + " too small for " + streamConfig.toString());
    if ((format == vision::PixelFormat::YUYV || format == vision::PixelFormat::NV12) &&
        (size.width % 2 != 0 || size.height % 2 != 0))
        fail("odd size " + streamConfig.toString() + " for a YUV format");
}

void LibcameraSource::Impl::allocateAndMap()
{
    allocator = std::make_unique<libcamera::FrameBufferAllocator>(camera);
    if (allocator->allocate(stream) < 0)
        fail("cannot allocate frame buffers");
    const auto& frameBuffers = allocator->buffers(stream);
    if (frameBuffers.size() < 2)
        fail("only " + std::to_string(frameBuffers.size()) + " frame buffer(s) allocated");

    const std::size_t plane0Bytes = static_cast<std::size_t>(stride) * size.height;
    for (std::size_t i = 0; i < frameBuffers.size(); ++i) {
        libcamera::FrameBuffer* buffer = frameBuffers[i].get();
        const auto& planes = buffer->planes();
        if (planes.empty())
            fail("frame buffer without planes");
        // Map each distinct dmabuf once, over every plane that lives in it.
        std::vector<const std::uint8_t*> planeAddress(planes.size(), nullptr);
        for (std::size_t p = 0; p < planes.size(); ++p) {
            if (planeAddress[p] != nullptr)
                continue;
            const int fd = planes[p].fd.get();
            std::size_t end = 0;
            for (const auto& other : planes)
                if (other.fd.get() == fd)
                    end = std::max<std::size_t>(end, std::size_t{other.offset} + other.length);
            void* address = mmap(nullptr, end, PROT_READ, MAP_SHARED, fd, 0);
            if (address == MAP_FAILED)
                fail(std::string("cannot map a frame buffer: ") + std::strerror(errno));
            mappings.push_back({address, end});
            for (std::size_t q = 0; q < planes.size(); ++q)
                if (planes[q].fd.get() == fd)
                    planeAddress[q] = static_cast<const std::uint8_t*>(address) + planes[q].offset;
        }
        MappedBuffer mapped{planeAddress[0], planes.size() > 1 ? planeAddress[1] : nullptr};
        if (planes[0].length < (format == vision::PixelFormat::NV12 && planes.size() == 1
                                    ? plane0Bytes + plane0Bytes / 2
                                    : plane0Bytes))
            fail("frame buffer smaller than a frame");
        // Our NV12 view keeps chroma right after luma: say so now rather than draw garbage.
        if (format == vision::PixelFormat::NV12 && mapped.plane1 != nullptr &&
            mapped.plane1 != mapped.plane0 + plane0Bytes)
            fail("NV12 chroma plane is not contiguous with the luma plane");
        buffers.push_back(mapped);

        std::unique_ptr<libcamera::Request> request = camera->createRequest(i);
        if (!request)
            fail("cannot create a request");
        if (request->addBuffer(stream, buffer) < 0)
            fail("cannot add a buffer to a request");
        requests.push_back(std::move(request));
    }
    ring.assign(requests.size(), nullptr);
}

void LibcameraSource::Impl::start(double fps)
{
    camera->requestCompleted.connect(this, &Impl::requestComplete);
    if (fps > 0.0 && camera->controls().count(libcamera::controls::FrameDurationLimits.id()) > 0) {
        const std::int64_t frameUs = static_cast<std::int64_t>(1e6 / fps);
        startControls.set(libcamera::controls::FrameDurationLimits,
                          libcamera::Span<const std::int64_t, 2>({frameUs, frameUs}));
    }
    if (const int ret = camera->start(&startControls); ret < 0)
        fail(std::string("cannot start the camera: ") + std::strerror(-ret));
    started = true;
    for (const auto& request : requests)
        if (const int ret = camera->queueRequest(request.get()); ret < 0)
            fail(std::string("cannot queue a request: ") + std::strerror(-ret));
}

void LibcameraSource::Impl::close() noexcept
{
    bool gone = false;
    if (camera) {
        {
            std::lock_guard lock(mutex);
            gone = deviceGone || disconnected || (started && anyRequestCancelled());
        }
        camera->requestCompleted.disconnect(this);
        camera->disconnected.disconnect(this);
    }
    for (const Mapping& m : mappings)
        munmap(m.address, m.length);
    mappings.clear();
    if (started && gone) {
        park();
        return;
    }
    if (started)
        camera->stop();  // completes the queued requests as cancelled, synchronously
    requests.clear();
    allocator.reset();
    if (camera && acquired)
        camera->release();
    config.reset();
    camera.reset();
    manager.reset();  // stops it
}

void LibcameraSource::Impl::park() noexcept
{
    // libcamera 0.0.3 cannot let go of a running camera whose device vanished: stopping it trips
    // a fatal assertion (PipelineHandler::stop, "queuedRequests_.empty()": VIDIOC_STREAMOFF fails
    // and the queued buffers never return) and destroying it running ends in std::terminate (a
    // thread still joinable). So its objects are kept, reachable, for the rest of the process,
    // and since only one CameraManager may exist, no camera can be opened again until restart.
    // Reachable from this pointer, so leak checkers do not count them.
    static ParkedCamera* parked = new ParkedCamera;
    parked->manager = std::move(manager);
    parked->camera = std::move(camera);
    parked->config = std::move(config);
    parked->allocator = std::move(allocator);
    parked->requests = std::move(requests);
    restartRequired().store(true);
}

// libcamera's thread.
void LibcameraSource::Impl::requestComplete(libcamera::Request* request)
{
    if (request->status() == libcamera::Request::RequestCancelled)
        return;
    {
        std::lock_guard lock(mutex);
        // Every request is at most once in the ring, so it never overflows.
        ring[(ringHead + ringCount) % ring.size()] = request;
        ++ringCount;
    }
    arrived.notify_one();
}

// libcamera's thread.
void LibcameraSource::Impl::onDisconnected()
{
    {
        std::lock_guard lock(mutex);
        disconnected = true;
    }
    arrived.notify_one();
}

bool LibcameraSource::Impl::anyRequestCancelled() const noexcept
{
    // libcamera cancels a request it cannot queue to the device ("No such device" once the camera
    // is unplugged) but hands requests back in queueing order, so a cancelled one waits behind
    // the older ones that the vanished device will never return: we look at the status instead.
    // (Written by libcamera's thread; a stale read only delays the detection by one check.)
    for (const auto& request : requests)
        if (request->status() == libcamera::Request::RequestCancelled)
            return true;
    return false;
}

bool LibcameraSource::Impl::requeue(libcamera::Request* request) noexcept
{
    request->reuse(libcamera::Request::ReuseBuffers);
    const int ret = camera->queueRequest(request);
    if (ret < 0) {
        std::snprintf(error, sizeof error, "libcamera: %s: cannot queue a request: %s",
                      name.c_str(), std::strerror(-ret));
        return false;
    }
    return true;
}

SourceStatus LibcameraSource::Impl::lose(const char* why) noexcept
{
    lost = true;
    std::snprintf(error, sizeof error, "libcamera: %s: %s", name.c_str(), why);
    return SourceStatus::Lost;
}

SourceStatus LibcameraSource::Impl::next(vision::Frame& frame) noexcept
{
    lastWaitNs = 0;
    if (lost)
        return SourceStatus::Lost;
    if (held != nullptr) {
        libcamera::Request* previous = held;
        held = nullptr;
        if (!requeue(previous)) {
            lost = true;
            return SourceStatus::Lost;
        }
    }

    const std::int64_t startNs = monotonicNs();
    const std::int64_t deadlineNs = startNs + (sequence == 0 ? firstFrameTimeoutNs : timeoutNs);
    for (;;) {
        libcamera::Request* newest = nullptr;
        {
            std::unique_lock lock(mutex);
            while (ringCount == 0 && !disconnected && !deviceGone) {
                const std::int64_t left = deadlineNs - monotonicNs();
                if (left <= 0)
                    break;
                arrived.wait_for(lock, std::chrono::nanoseconds(std::min(left, kGoneCheckNs)));
                deviceGone = deviceGone || anyRequestCancelled();
            }
            if (disconnected || deviceGone) {
                lastWaitNs = monotonicNs() - startNs;
                return lose(disconnected ? "camera disconnected"
                                         : "camera gone (libcamera cancelled a request)");
            }
            if (ringCount == 0) {
                lastWaitNs = monotonicNs() - startNs;
                char why[64];
                std::snprintf(why, sizeof why, "no frame for %.1f s (camera stalled)",
                              static_cast<double>(deadlineNs - startNs) / 1e9);
                return lose(why);
            }
            // Keep the newest; give the older ones straight back to the camera.
            while (ringCount > 0) {
                libcamera::Request* r = ring[ringHead];
                ringHead = (ringHead + 1) % ring.size();
                --ringCount;
                if (newest != nullptr) {
                    ++dropped;
                    lock.unlock();
                    const bool ok = requeue(newest);
                    lock.lock();
                    if (!ok) {
                        lost = true;
                        return SourceStatus::Lost;
                    }
                }
                newest = r;
            }
        }
        lastWaitNs = monotonicNs() - startNs;

        const libcamera::FrameBuffer* buffer = newest->findBuffer(stream);
        if (newest->status() != libcamera::Request::RequestComplete || buffer == nullptr ||
            buffer->metadata().status != libcamera::FrameMetadata::FrameSuccess) {
            ++failed;
            if (!requeue(newest)) {
                lost = true;
                return SourceStatus::Lost;
            }
            if (monotonicNs() >= deadlineNs)
                return lose("camera delivers only failed frames");
            continue;
        }

        held = newest;
        const MappedBuffer& mapped = buffers[newest->cookie()];
        frame.image = {mapped.plane0, size.width, size.height, stride, format};
        frame.sequence = sequence++;
        const std::optional<std::int64_t> sensorNs =
            newest->metadata().get(libcamera::controls::SensorTimestamp);
        frame.timestampNs =
            sensorNs ? *sensorNs : static_cast<std::int64_t>(buffer->metadata().timestamp);
        return SourceStatus::Ok;
    }
}

LibcameraSource::LibcameraSource(const LibcameraOptions& options) : impl_(std::make_unique<Impl>())
{
    try {
        impl_->open(options);
    } catch (...) {
        impl_->close();
        throw;
    }
}

LibcameraSource::~LibcameraSource()
{
    impl_->close();
}

const char* LibcameraSource::description() const noexcept
{
    return impl_->description.c_str();
}

vision::Size LibcameraSource::size() const noexcept
{
    return impl_->size;
}

vision::PixelFormat LibcameraSource::format() const noexcept
{
    return impl_->format;
}

SourceStatus LibcameraSource::next(vision::Frame& frame) noexcept
{
    return impl_->next(frame);
}

std::int64_t LibcameraSource::lastWaitNs() const noexcept
{
    return impl_->lastWaitNs;
}

const char* LibcameraSource::lastError() const noexcept
{
    return impl_->error;
}

bool LibcameraSource::needsProcessRestart() const noexcept
{
    return restartRequired().load();
}

std::uint64_t LibcameraSource::failedFrames() const noexcept
{
    return impl_->failed;
}

std::uint64_t LibcameraSource::droppedFrames() const noexcept
{
    return impl_->dropped;
}

bool libcameraRestartRequired() noexcept
{
    return restartRequired().load();
}

bool libcameraCameraAvailable() noexcept
{
    if (restartRequired().load())
        return false;  // a second CameraManager would abort the process
    try {
        quietLibcameraLogs();
        libcamera::CameraManager manager;
        if (manager.start() < 0)
            return false;
        return !manager.cameras().empty();
    } catch (...) {
        return false;
    }
}

}  // namespace platform
