#include "platform/reconnecting_source.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <utility>

namespace platform {

const char* cameraStateName(CameraState state) noexcept
{
    switch (state) {
        case CameraState::Running:
            return "running";
        case CameraState::Lost:
            return "lost";
        case CameraState::Retrying:
            return "retrying";
    }
    return "?";
}

ReconnectingSource::ReconnectingSource(std::string name, SourceOpener open,
                                       vision::Size expectedSize,
                                       vision::PixelFormat expectedFormat, ReconnectOptions options,
                                       PacerClock& clock)
    : name_(std::move(name)),
      open_(std::move(open)),
      options_(options),
      clock_(&clock),
      size_(expectedSize),
      format_(expectedFormat)
{
    options_.firstRetryNs = std::max<std::int64_t>(options_.firstRetryNs, 1'000'000);
    options_.maxRetryNs = std::max(options_.maxRetryNs, options_.firstRetryNs);
    delayNs_ = options_.firstRetryNs;
    std::snprintf(unavailable_, sizeof unavailable_, "%s (unavailable)", name_.c_str());
    if (tryOpen()) {
        state_ = CameraState::Running;
    } else {
        // Missing at boot: Lost until the first retry, like a camera that just went away.
        failedAttempts_ = 0;
        delayNs_ = options_.firstRetryNs;
        nextAttemptNs_ = clock_->nowNs() + delayNs_;
    }
    sizeFixed_ = true;  // from here on size() and format() are the pipeline's
}

ReconnectingSource::~ReconnectingSource() = default;

const char* ReconnectingSource::description() const noexcept
{
    return inner_ ? inner_->description() : unavailable_;
}

void ReconnectingSource::setState(CameraState state) noexcept
{
    if (state != state_) {
        state_ = state;
        ++transitions_;
    }
}

void ReconnectingSource::failed(const char* why) noexcept
{
    std::snprintf(error_, sizeof error_, "%s", why);
}

/// Opens a new inner source; on failure records why and schedules the next attempt.
bool ReconnectingSource::tryOpen() noexcept
{
    inner_.reset();  // never two at once: a camera can be opened by one owner only
    try {
        std::unique_ptr<FrameSource> source = open_();
        if (!source)
            throw std::runtime_error(name_ + ": no source");
        needsRebuild_ = false;
        if (sizeFixed_ && (source->size() != size_ || source->format() != format_)) {
            needsRebuild_ = true;
            std::snprintf(error_, sizeof error_,
                          "%s: camera came back as %dx%d %s, the mirror runs %dx%d %s (restart "
                          "the pipeline to adopt it)",
                          name_.c_str(), source->size().width, source->size().height,
                          vision::pixelFormatName(source->format()), size_.width, size_.height,
                          vision::pixelFormatName(format_));
        } else {
            size_ = source->size();
            format_ = source->format();
            if (everOpened_)
                ++reconnects_;
            everOpened_ = true;
            inner_ = std::move(source);
            error_[0] = '\0';
            failedAttempts_ = 0;
            delayNs_ = options_.firstRetryNs;
            return true;
        }
    } catch (const std::exception& e) {
        failed(e.what());
    } catch (...) {
        std::snprintf(error_, sizeof error_, "%s: cannot open (unknown error)", name_.c_str());
    }
    // Waits after a loss: firstRetryNs, then 2x, 4x ... up to maxRetryNs between failed attempts.
    ++failedAttempts_;
    delayNs_ = std::min(delayNs_ * 2, options_.maxRetryNs);
    nextAttemptNs_ = clock_->nowNs() + delayNs_;
    return false;
}

SourceStatus ReconnectingSource::next(vision::Frame& frame) noexcept
{
    lastWaitNs_ = 0;
    if (!inner_) {
        if (clock_->nowNs() < nextAttemptNs_)
            return SourceStatus::Lost;
        if (!tryOpen()) {
            setState(CameraState::Retrying);
            return SourceStatus::Lost;
        }
        setState(CameraState::Running);
    }

    const SourceStatus status = inner_->next(frame);
    lastWaitNs_ = inner_->lastWaitNs();
    if (status == SourceStatus::Ok) {
        frame.sequence = sequence_++;
        return SourceStatus::Ok;
    }
    if (status == SourceStatus::EndOfStream)
        return status;

    // Lost: release the device now; the first retry comes after the shortest delay.
    std::snprintf(error_, sizeof error_, "%s", inner_->lastError());
    if (error_[0] == '\0')
        std::snprintf(error_, sizeof error_, "%s: camera lost", name_.c_str());
    inner_.reset();
    failedAttempts_ = 0;
    delayNs_ = options_.firstRetryNs;
    nextAttemptNs_ = clock_->nowNs() + delayNs_;
    setState(CameraState::Lost);
    return SourceStatus::Lost;
}

}  // namespace platform
