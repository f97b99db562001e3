// Must-hold of the skeleton: zero heap allocations per frame in the steady-state loop
// (synthetic source -> vision -> render -> headless display), counted over 300 frames; and on
// real faces, with and without the AAM fit (§5.3) running on them.
#include "alloc_counter.hpp"
#include "fake_console.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "preloaded_face_source.hpp"
#include "test_paths.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

TEST(FrameLoopAllocations, SteadyStateLoopMakesNoHeapAllocations)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";

    firmware::Config config;
    config.source.spec = "synthetic";
    config.source.rate.kind = firmware::Rate::Kind::Max;
    config.source.card = firmware::SourceConfig::Card::On;
    config.display.spec = "headless:" + testing_support::freshOutputDir("frame_loop_alloc");
    config.display.width = 640;
    config.display.height = 360;
    config.display.hud = true;
    config.display.snapshotEvery = 100;  // snapshots inside the counted frames too
    config.log.summaryIntervalS = 0.05;  // summaries inside the counted frames too
    config.state.dir = testing_support::freshOutputDir("frame_loop_alloc_state");
    const int devNull = ::open("/dev/null", O_WRONLY);
    firmware::setLogFd(devNull);

    firmware::FrameLoop loop(config, firmware::makeSource(config.source),
                             firmware::makeDisplay(config.display));
    FakeConsole console;
    loop.attachConsole(&console);

    // Warm up: first frames create driver state, caches and the first snapshot.
    for (int i = 0; i < 30; ++i)
        ASSERT_TRUE(loop.step());

    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        for (int i = 0; i < 300; ++i) {
            // The console path is part of the loop: a command every 50 frames.
            if (i % 50 == 10)
                console.type(i % 100 == 10 ? "status\n" : "snapshot\nhelp\n");
            if (!loop.step())
                break;
        }
        counts = scope.counts();
    }
    firmware::setLogFd(2);
    ::close(devNull);

    EXPECT_EQ(loop.framesShown(), 330u);
    EXPECT_NE(console.output().find("stage"), std::string_view::npos) << console.output();
    EXPECT_NE(console.output().find("snapshot: "), std::string_view::npos) << console.output();
    std::printf(
        "allocations over 300 frames: operator new %ld, our malloc %ld; GL driver and other "
        "shared libraries: malloc %ld (%.1f per frame), operator new %ld (its shader compiler)\n",
        counts.cxxNew, counts.ownMalloc, counts.foreignMalloc,
        static_cast<double>(counts.foreignMalloc) / 300.0, counts.foreignNew);
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}

}  // namespace

namespace {

/// What a run of the loop on real faces (the FGNet talking face) counted.
struct RealFacesRun {
    testing_support::AllocationCounts counts;
    int framesWithFace = 0;
    int framesFitted = 0;  ///< frames with an AAM fit that holds (ok) on a shown face
    long fitIterations = 0;
    int fits = 0;
    int okFits = 0, okFitsInTheirBox = 0;  ///< the fits' eyes in frame coordinates, in the box
    std::string console;
};

/// 30 warm-up frames, then 200 counted ones with console commands among them.
RealFacesRun runRealFaces(const std::string& name, const std::string& model)
{
    firmware::Config config;
    config.source.spec = "preloaded";
    config.display.spec = "headless:" + testing_support::freshOutputDir(name);
    config.display.width = 640;
    config.display.height = 360;
    config.display.hud = true;
    config.display.debug = true;  // the face debug layer (and the fitted mesh) inside the count
    config.display.snapshotEvery = 100;
    config.log.summaryIntervalS = 0.05;
    config.card.enabled = false;
    config.faces.enabled = true;
    config.faces.model = model;
    config.state.dir = testing_support::freshOutputDir(name + "_state");
    const int devNull = ::open("/dev/null", O_WRONLY);
    firmware::setLogFd(devNull);

    RealFacesRun run;
    {
        firmware::FrameLoop loop(config, std::make_unique<PreloadedFaceSource>(40),
                                 firmware::makeDisplay(config.display));
        FakeConsole console;
        loop.attachConsole(&console);
        for (int i = 0; i < 30; ++i)
            EXPECT_TRUE(loop.step());

        {
            testing_support::AllocationScope scope;
            for (int i = 0; i < 200; ++i) {
                if (i % 50 == 10)
                    console.type(i % 100 == 10 ? "faces\n" : "status\ndebug off\ndebug on\n");
                if (!loop.step())
                    break;
                const vision::FrameState& state = loop.lastFrameState();
                for (const vision::TrackedFace& f : state.faces)
                    if (f.shown()) {
                        ++run.framesWithFace;
                        break;
                    }
                bool fitted = false;
                for (const vision::FaceFit& fit : state.fits) {
                    if (!fit.fitted)
                        continue;
                    ++run.fits;
                    run.fitIterations += fit.iterations;
                    fitted = fitted || fit.ok();
                    if (!fit.ok())
                        continue;
                    ++run.okFits;
                    for (const vision::TrackedFace& f : state.faces)
                        if (f.id == fit.faceId &&
                            std::abs(fit.eyeMidpoint.x - f.centre.x) < 0.5f * f.size &&
                            std::abs(fit.eyeMidpoint.y - f.centre.y) < 0.5f * f.size)
                            ++run.okFitsInTheirBox;
                }
                run.framesFitted += fitted;
            }
            run.counts = scope.counts();
        }
        EXPECT_EQ(loop.framesShown(), 230u);
        run.console = std::string(console.output());
    }
    firmware::setLogFd(2);
    ::close(devNull);
    return run;
}

TEST(FrameLoopAllocations, TrackingRealFacesMakesNoHeapAllocations)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    const RealFacesRun run = runRealFaces("frame_loop_alloc_faces", "");
    EXPECT_GE(run.framesWithFace, 195) << "the face should be shown in (nearly) every counted frame";
    EXPECT_NE(run.console.find("face 1: shown"), std::string::npos) << run.console;
    std::printf(
        "faces: shown in %d of 200 counted frames; allocations: operator new %ld, our "
        "malloc %ld, GL driver and other shared libraries %ld\n",
        run.framesWithFace, run.counts.cxxNew, run.counts.ownMalloc, run.counts.foreignMalloc);
    EXPECT_EQ(run.counts.cxxNew, 0);
    EXPECT_EQ(run.counts.ownMalloc, 0);
}

TEST(FrameLoopAllocations, FittingTheAamToRealFacesMakesNoHeapAllocations)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    const std::string model = testing_support::sourceDir() + "/out/aam/imm-demo.aam";
    if (!std::filesystem::exists(model))
        GTEST_SKIP() << "out/aam/imm-demo.aam is not built (scripts/dev model)";
    const RealFacesRun run = runRealFaces("frame_loop_alloc_aam", model);
    EXPECT_GE(run.framesWithFace, 195);
    EXPECT_GE(run.fits, 195) << "every shown face is fitted";
    EXPECT_EQ(run.okFitsInTheirBox, run.okFits) << "fits in frame coordinates, on their face";
    EXPECT_NE(run.console.find("face 1: aam "), std::string::npos) << run.console;
    EXPECT_NE(run.console.find("jaw_drop"), std::string::npos) << run.console;
    std::printf(
        "aam: %d fits in 200 counted frames, %d frames with a fit that holds, %.1f iterations "
        "per fit; allocations: operator new %ld, our malloc %ld, GL driver and other shared "
        "libraries %ld\n",
        run.fits, run.framesFitted,
        static_cast<double>(run.fitIterations) / std::max(run.fits, 1), run.counts.cxxNew,
        run.counts.ownMalloc, run.counts.foreignMalloc);
    EXPECT_EQ(run.counts.cxxNew, 0);
    EXPECT_EQ(run.counts.ownMalloc, 0);
}

}  // namespace
