#pragma once
// FrameLoop: the appliance's main loop. Per frame: poll the console, take a frame from the source,
// run the vision stages, handle the inputs and overlays, draw with the renderer, present on the
// display; time every step (docs/ARCHITECTURE.md, "The life of one frame").
//
// Ownership: the loop owns the source, the display, the pipeline (built by buildPipeline; through
// it every stage buffer), the renderer and what it does with the results (CardControl,
// FaceControl, OverlayControl, PeopleControl: their layers and kept state); all of them are built
// before the first frame. step() never throws and never allocates: device errors become states
// (source lost, display unavailable) that are logged once when they begin and once when they end.

#include "firmware/button_actions.hpp"
#include "firmware/command_shell.hpp"
#include "firmware/config.hpp"
#include "firmware/device_wait.hpp"
#include "firmware/latency_histogram.hpp"
#include "firmware/overlay_selection.hpp"
#include "platform/button_input.hpp"
#include "platform/console.hpp"
#include "platform/display.hpp"
#include "platform/frame_source.hpp"
#include "platform/service_notifier.hpp"
#include "render/renderer.hpp"
#include "vision/pipeline.hpp"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace firmware {

class BugReportWorker;
class CardControl;
class FaceControl;
class OverlayControl;
class PeopleControl;

/// Timing of one named step of the frame: since start, and since the last summary.
struct StepTiming {
    const char* name = "";
    LatencyHistogram total;
    LatencyHistogram interval;
};

class FrameLoop {
public:
    static constexpr std::size_t kMaxSteps = vision::Pipeline::kMaxStages + 4;

    /// Builds the pipeline and renderer for the source's size and format. Throws on failure.
    FrameLoop(const Config& config, std::unique_ptr<platform::FrameSource> source,
              std::unique_ptr<platform::Display> display);
    ~FrameLoop();
    FrameLoop(const FrameLoop&) = delete;
    FrameLoop& operator=(const FrameLoop&) = delete;

    /// The console the shell reads commands from and answers on (not owned; may be null); a
    /// terminal gets a prompt.
    void attachConsole(platform::Console* console, bool terminal = false) noexcept
    {
        consoles_[0] = console;
        shell_.setChannelStyle(0, terminal, /*crlf=*/false);
    }
    /// A second console (the serial port), served by the same shell with its own line assembly.
    void attachSerialConsole(platform::Console* console) noexcept
    {
        consoles_[1] = console;
        shell_.setChannelStyle(1, /*prompt=*/true, /*crlf=*/true);  // a terminal on a UART
    }
    /// The buttons on the frame (owned from now on; null: none).
    void attachButtons(std::unique_ptr<platform::ButtonInput> buttons) noexcept
    {
        buttons_ = std::move(buttons);
    }
    /// What an `auto` source or display that found nothing waits for (owned; null: nothing).
    /// When it comes the loop stops for the pipeline to be rebuilt on it (restartRequested()).
    void attachDeviceWait(std::unique_ptr<DeviceWait> wait) noexcept
    {
        deviceWait_ = std::move(wait);
    }
    /// Who wears what (null when overlays are off or could not be loaded).
    const OverlaySelection* overlaySelection() const noexcept;

    /// Runs until `maxFrames` frames were shown (0 = no limit), `quit`, requestStop(), the end
    /// of a finite source, or a source that needs a new process. Returns an exit code: kExitOk
    /// when it stopped as asked, kExitSource when the source needs a new process.
    int run(std::uint64_t maxFrames) noexcept;
    /// One iteration: the steps of docs/ARCHITECTURE.md's "life of one frame". False when the
    /// loop should stop.
    bool step() noexcept;
    /// Safe from a signal handler.
    void requestStop() noexcept { stop_.store(true); }

    std::uint64_t framesShown() const noexcept { return framesShown_; }
    const vision::FrameState& lastFrameState() const noexcept { return state_; }
    platform::Display& display() noexcept { return *display_; }
    /// True when the loop stopped because `reboot-mirror`, a camera back in another size, or an
    /// awaited device that came asked for the pipeline to be rebuilt (main then builds source,
    /// display and loop again; the process and console stay).
    bool restartRequested() const noexcept { return restart_; }
    /// True when the loop stopped because its source can deliver no frame again in this process
    /// (FrameSource::needsProcessRestart): main then ends the process at once, with run()'s
    /// exit code and without static destructors, for the service manager to start a new one.
    bool processRestartRequired() const noexcept { return processRestart_; }
    /// Whether the debug HUD (face boxes, corners, roll axes) is shown.
    bool debugHud() const noexcept;

    /// The mirror executable (for the bug report's camera list, run as a new process).
    void setProgramPath(std::string path);
    /// `mirror --bug-report FILE`: after `afterS` seconds of running, write a bug report to
    /// `path` (as the console's `bug-report` does), then stop.
    void scheduleBugReport(std::string path, double afterS);
    /// True when a scheduled bug report could not be written.
    bool bugReportFailed() const noexcept { return bugReportFailed_; }

private:
    // The steps of one frame, in order (frame_loop.cpp).
    std::int64_t startIteration() noexcept;
    bool serveConsoles() noexcept;
    platform::SourceStatus capture(std::int64_t startNs) noexcept;
    bool waitForSource() noexcept;
    bool runVision() noexcept;
    void noteVisionResults() noexcept;
    void handleInputsAndOverlays() noexcept;
    bool render() noexcept;
    std::int64_t present() noexcept;
    bool finishIteration(std::int64_t nowNs) noexcept;

    void noteSourceStatus(platform::SourceStatus status) noexcept;
    void showSourceLost(std::int64_t nowNs) noexcept;
    void updateRate(std::int64_t nowNs) noexcept;
    void writeSummary() noexcept;
    bool summaryWorthLogging(std::int64_t nowNs) noexcept;
    /// After a frame was shown: the consoles that asked for a snapshot are told its path, and a
    /// bug report waiting for it goes on.
    void afterPresent() noexcept;
    void formatHud() noexcept;
    void record(std::size_t step, std::int64_t ns) noexcept
    {
        timings_[step].total.record(ns);
        timings_[step].interval.record(ns);
    }
    void tellConsoles(const char* text) noexcept;

    // Inputs (frame_inputs.cpp): the buttons and a display's own keyboard do what the console
    // commands do.
    void pollButtons() noexcept;
    void pollKeys() noexcept;
    void runButtonAction(ButtonAction action) noexcept;
    void requestCardTraining() noexcept;
    void setDebugHud(bool on) noexcept;

    // The console (console_commands.cpp, self_test.cpp).
    void registerCommands();
    void formatStatus(Reply& reply) const noexcept;
    /// `status --json`: the same facts as one JSON object, for field tools.
    void formatStatusJson(Reply& reply) const noexcept;
    void snapshotCommand(Reply& reply) noexcept;
    // The bug report (loop_bug_report.cpp).
    void bugReportCommand(const Args& args, Reply& reply) noexcept;
    void gatherBugReport() noexcept;
    void startBugReport(const char* snapshot) noexcept;
    void serviceBugReport(std::int64_t nowNs) noexcept;
    void buttonsCommand(Reply& reply) noexcept;
    /// Writes the self-test report (as `selftest` prints it): one PASS/FAIL/SKIP line per check.
    /// Returns the number of FAILs.
    int selfTest(Reply& reply) const noexcept;

    Config config_;
    std::string configToml_;  // effective config, rendered once at start-up for `config`
    std::unique_ptr<platform::FrameSource> source_;
    std::unique_ptr<platform::Display> display_;
    std::unique_ptr<render::Renderer> renderer_;
    vision::Pipeline pipeline_;
    vision::FrameState state_;
    vision::Frame frame_;
    CommandShell shell_;
    /// [0] standard input, [1] the serial port; either may be null.
    std::array<platform::Console*, CommandShell::kChannels> consoles_{};

    // What the loop does with the vision results besides drawing the frame; each is null when
    // the config leaves its stages out (overlays: always there, maybe with nothing loaded).
    std::unique_ptr<CardControl> card_;
    std::unique_ptr<OverlayControl> overlays_;
    std::unique_ptr<FaceControl> faces_;
    std::unique_ptr<PeopleControl> people_;  ///< who the faces are (null without faces)

    // Buttons on the frame (null: none or unavailable) and what their presses do.
    std::unique_ptr<platform::ButtonInput> buttons_;
    std::unique_ptr<DeviceWait> deviceWait_;
    ButtonActions buttonActions_;
    bool buttonsFailed_ = false;  // poll failed: logged once, then silent

    // Steps: wait (idle until the frame is due), capture (decode, copy), the vision stages from
    // kFirstVisionStep on, then render and present.
    static constexpr std::size_t kWaitStep = 0;
    static constexpr std::size_t kCaptureStep = 1;
    static constexpr std::size_t kFirstVisionStep = 2;
    std::array<StepTiming, kMaxSteps> timings_{};
    std::size_t stepCount_ = 0;
    std::size_t renderStep_ = 0;
    std::size_t presentStep_ = 0;

    // systemd: READY after the first frame or "camera unavailable" screen shown, a watchdog
    // keep-alive from every iteration (a stalled loop stops them and gets restarted), a status
    // line on changes.
    platform::ServiceNotifier notifier_;
    std::atomic<bool> stop_{false};
    bool restart_ = false;
    bool processRestart_ = false;
    std::int64_t capturedNs_ = 0;       // when the source returned this iteration
    std::int64_t visionEndNs_ = 0;      // when this frame's last vision stage ended
    std::int64_t lastFrameNs_ = 0;      // when the source last delivered a frame
    std::int64_t frameIntervalNs_ = 0;  // running mean of the time between frames
    std::int64_t lastPresentNs_ = 0;    // when the display last showed one
    std::int64_t lostScreenNs_ = 0;     // when the "camera unavailable" screen was last drawn
    bool sourceEnded_ = false;
    bool sourceLost_ = false;
    bool frameBad_ = false;
    bool displayDown_ = false;
    /// Frames in a row whose drawing raised a GL error: the first is logged, then the recovery.
    std::uint64_t renderErrorFrames_ = 0;
    bool snapshotReplyPending_ = false;
    std::uint64_t framesShown_ = 0;
    std::uint64_t badFrames_ = 0;
    std::uint64_t lostPolls_ = 0;
    std::int64_t startNs_ = 0;
    std::int64_t intervalStartNs_ = 0;
    std::uint64_t intervalFrames_ = 0;
    double fps_ = 0.0;
    int summaryFd_ = -1;
    // The bug report: the loop's texts (status, status JSON, selftest, config, log), sized at
    // start-up, and the thread that writes the tarball.
    std::vector<Reply> bugTexts_;
    std::unique_ptr<BugReportWorker> bugReports_;
    char bugReportPath_[1024] = "";
    bool bugSnapshotWanted_ = false;
    std::int64_t bugRequestedNs_ = 0;
    std::string scheduledBugReport_;
    std::int64_t bugReportDueNs_ = 0;
    bool stopAfterBugReport_ = false;
    bool bugReportFailed_ = false;
    std::int64_t loggedSummaryNs_ = 0;  // when a summary last went to the log at Info
    double loggedFps_ = 0.0;            // its frame rate
    std::int64_t summaryBytes_ = 0;  // in summary.log now; started afresh past kMaxSummaryBytes
    char hud_[256] = "";
};

}  // namespace firmware
