#pragma once
// FrameLoop: the appliance's main loop. Per frame: poll the console, take a frame from the source,
// run the vision stages, draw with the renderer, present on the display; time every step.
//
// Ownership: the loop owns the source, the display, the pipeline (and through it every stage
// buffer) and the renderer; all of them are built before the first frame. step() never throws and
// never allocates: device errors become states (source lost, display unavailable) that are logged
// once when they begin and once when they end.

#include "firmware/button_actions.hpp"
#include "firmware/card_model_store.hpp"
#include "firmware/command_shell.hpp"
#include "firmware/config.hpp"
#include "firmware/face_smoother.hpp"
#include "firmware/latency_histogram.hpp"
#include "firmware/overlay_selection.hpp"
#include "firmware/overlay_state_store.hpp"
#include "platform/button_input.hpp"
#include "platform/console.hpp"
#include "platform/display.hpp"
#include "platform/frame_source.hpp"
#include "platform/service_notifier.hpp"
#include "render/card_picture_layer.hpp"
#include "render/face_debug_layer.hpp"
#include "render/face_overlay_layer.hpp"
#include "render/renderer.hpp"
#include "vision/card_stage.hpp"
#include "vision/face_stage.hpp"
#include "vision/motion_stage.hpp"
#include "vision/pipeline.hpp"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

namespace firmware {

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

    /// The console the shell reads commands from and answers on (not owned; may be null).
    void attachConsole(platform::Console* console) noexcept { consoles_[0] = console; }
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
    /// Who wears what (null when overlays are off or could not be loaded).
    const OverlaySelection* overlaySelection() const noexcept { return selection_.get(); }

    /// Runs until `maxFrames` frames were shown (0 = no limit), `quit`, requestStop(), the end
    /// of a finite source, or a source that needs a new process. Returns an exit code: kExitOk
    /// when it stopped as asked, kExitSource when the source needs a new process.
    int run(std::uint64_t maxFrames) noexcept;
    /// One iteration. False when the loop should stop.
    bool step() noexcept;
    /// Safe from a signal handler.
    void requestStop() noexcept { stop_.store(true); }

    std::uint64_t framesShown() const noexcept { return framesShown_; }
    std::uint64_t badFrames() const noexcept { return badFrames_; }
    const vision::FrameState& lastFrameState() const noexcept { return state_; }
    platform::Display& display() noexcept { return *display_; }
    render::Renderer& renderer() noexcept { return *renderer_; }
    CommandShell& shell() noexcept { return shell_; }
    /// Frames per second over the last summary interval.
    double fps() const noexcept { return fps_; }
    /// Writes the status report (as the `status` command prints it).
    void formatStatus(Reply& reply) const noexcept;
    /// The card tracker's stage, or null when [card] enabled = false.
    vision::CardStage* cardStage() noexcept { return cardStage_; }
    /// Trains the card colour on the next good frame (as `card train` does); the card stage does
    /// the training, the loop then keeps the colour and reports it.
    void requestCardTraining() noexcept;
    /// The face stage, or null when [faces] enabled = false.
    vision::FaceStage* faceStage() noexcept { return faceStage_; }
    /// Shows or hides the debug HUD (face boxes, corners, roll axes).
    void setDebugHud(bool on) noexcept;
    /// True when the loop stopped because `reboot-mirror` asked for the pipeline to be rebuilt
    /// (main then builds source, display and loop again; the process and console stay).
    bool restartRequested() const noexcept { return restart_; }
    /// True when the loop stopped because its source can deliver no frame again in this process
    /// (FrameSource::needsProcessRestart): main then ends the process at once, with run()'s
    /// exit code and without static destructors, for the service manager to start a new one.
    bool processRestartRequired() const noexcept { return processRestart_; }
    /// Writes the self-test report (as `selftest` prints it): one PASS/FAIL/SKIP line per check.
    /// Returns the number of FAILs.
    int selfTest(Reply& reply) const noexcept;
    bool debugHud() const noexcept { return faceDebug_ && faceDebug_->visible(); }

private:
    void buildPipeline(vision::Size size, vision::PixelFormat format);
    void setUpCard(vision::Size size);
    void reportCardTraining() noexcept;
    void noteCardState() noexcept;
    void formatCard(Reply& reply) const noexcept;
    void addFaceStages(vision::Size size);
    void setUpOverlays(vision::Size size);
    void warmUpOverlays(vision::Size size);
    void pollButtons() noexcept;
    void pollKeys() noexcept;
    void runButtonAction(ButtonAction action) noexcept;
    void updateOverlays() noexcept;
    void overlayCommand(const Args& args, Reply& reply) noexcept;
    void formatOverlays(Reply& reply) const noexcept;
    void noteFaces() noexcept;
    void formatFaces(Reply& reply) const noexcept;
    void registerCommands();
    void stepSource() noexcept;
    void noteSourceStatus(platform::SourceStatus status) noexcept;
    void showSourceLost(std::int64_t nowNs) noexcept;
    void updateRate(std::int64_t nowNs) noexcept;
    void writeSummary() noexcept;
    void formatHud() noexcept;
    void record(std::size_t step, std::int64_t ns) noexcept
    {
        timings_[step].total.record(ns);
        timings_[step].interval.record(ns);
    }

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
    void tellConsoles(const char* text) noexcept;

    // The colour card (ch. 4): its stage lives in the pipeline; the picture layer in the renderer.
    vision::CardStage* cardStage_ = nullptr;
    std::unique_ptr<CardModelStore> cardStore_;
    std::unique_ptr<render::CardPictureLayer> cardLayer_;
    vision::CardState cardState_ = vision::CardState::Untrained;
    bool cardTrainPending_ = false;  // asked for; reported once the stage has trained

    // Faces (5.1-5.2): both stages live in the pipeline; the debug layer in the renderer.
    vision::MotionStage* motionStage_ = nullptr;
    vision::FaceStage* faceStage_ = nullptr;
    std::unique_ptr<render::FaceDebugLayer> faceDebug_;
    int facesShown_ = 0;  // shown faces last frame, for logging changes once

    // Overlays (5.4): the layer in the renderer, who wears what, and what is kept across restarts.
    std::unique_ptr<render::FaceOverlayLayer> overlayLayer_;
    std::unique_ptr<OverlaySelection> selection_;
    std::unique_ptr<OverlayStateStore> overlayStore_;
    std::uint32_t savedGeneration_ = 0;
    FaceSmoother smoother_;
    std::string overlaysProblem_;  // why overlays are off although enabled ("" when fine)

    // Buttons on the frame (null: none or unavailable) and what their presses do.
    std::unique_ptr<platform::ButtonInput> buttons_;
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

    // systemd: READY after the first frame shown, a watchdog keep-alive from every iteration (a
    // stalled loop stops them and gets restarted), a status line on changes.
    platform::ServiceNotifier notifier_;
    std::atomic<bool> stop_{false};
    bool restart_ = false;
    bool processRestart_ = false;
    std::int64_t lastFrameNs_ = 0;      // when the source last delivered a frame
    std::int64_t frameIntervalNs_ = 0;  // running mean of the time between frames
    std::int64_t lastPresentNs_ = 0;    // when the display last showed one
    std::int64_t lostScreenNs_ = 0;     // when the "camera unavailable" screen was last drawn
    bool sourceEnded_ = false;
    bool sourceLost_ = false;
    bool frameBad_ = false;
    bool displayDown_ = false;
    bool snapshotReplyPending_ = false;
    std::uint64_t framesShown_ = 0;
    std::uint64_t badFrames_ = 0;
    std::int64_t startNs_ = 0;
    std::int64_t intervalStartNs_ = 0;
    std::uint64_t intervalFrames_ = 0;
    double fps_ = 0.0;
    int summaryFd_ = -1;
    char hud_[256] = "";
};

}  // namespace firmware
