// The people the mirror knows, for people to look at (docs/snapshots/README.md says how the
// pictures go into docs/snapshots/): facegen composes moving IMM persons the demo model never saw
// (04 "tom", 08 "anna", 12 a stranger) over photographs; the frame loop, with the real pipeline
// and the demo AAM model, enrols tom and anna from the console each alone in view, each choosing
// an overlay of their own; then, after a restart, both in view wear their own overlays; on anna's
// birthday (with the birthday first in [overlay] precedence) she alone wears the birthday hat;
// and on a rainy day the stranger, a guest, wears the weather's rain hat. The test asserts who
// each face is and what it wears, and writes each picture with the console's `snapshot`.
#include "fake_console.hpp"
#include "firmware/day_calendar.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/log.hpp"
#include "overlay_loop_config.hpp"
#include "preloaded_face_source.hpp"
#include "test_paths.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string demoModel()
{
    return testing_support::sourceDir() + "/out/aam/imm-demo.aam";
}

std::string facegen()
{
    return testing_support::binaryDir() + "/bin/facegen";
}

/// A facegen sequence's frames, decoded before the loop runs, played forwards then backwards.
std::unique_ptr<PreloadedFaceSource> sequenceSource(const std::string& dir)
{
    std::vector<std::string> paths;
    for (int i = 0;; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "/frames/%06d.png", i);
        if (!fs::exists(dir + name))
            break;
        paths.push_back(dir + name);
    }
    return std::make_unique<PreloadedFaceSource>(paths, 33333333);
}

/// "MM-DD" of today (local time), or of a day that is not today (next month's first).
std::string monthDay(bool today)
{
    if (today)
        return todayMonthDay();
    char text[8];
    std::snprintf(text, sizeof text, "%02d-01",
                  firmware::localDay(std::time(nullptr)).month % 12 + 1);
    return text;
}

struct Mirror {
    Mirror(const firmware::Config& config, const std::string& sequence)
        : loop(config, sequenceSource(sequence), firmware::makeDisplay(config.display))
    {
        loop.attachConsole(&console);
    }
    std::string run(const std::string& line)
    {
        console.clearOutput();
        command_ = line + "\n";
        console.type(command_.c_str());
        EXPECT_TRUE(loop.step());
        return std::string(console.output());
    }
    bool stepUntil(const std::function<bool()>& done, int frames)
    {
        for (int i = 0; i < frames; ++i) {
            if (done())
                return true;
            if (!loop.step())
                return false;
        }
        return done();
    }
    std::vector<int> shownFaces() const
    {
        std::vector<int> ids;
        for (const vision::TrackedFace& f : loop.lastFrameState().faces)
            if (f.shown())
                ids.push_back(f.id);
        return ids;
    }
    /// `count` faces shown, each with its signature settled (recognition has decided).
    bool settled(std::size_t count) const
    {
        const std::vector<int> ids = shownFaces();
        if (ids.size() != count)
            return false;
        for (int id : ids) {
            const vision::FaceFit* fit = vision::fitFor(loop.lastFrameState().fits, id);
            if (fit == nullptr || !fit->signatureSettled)
                return false;
        }
        return true;
    }
    /// What face `id` wears now.
    std::string wears(int id) const
    {
        const firmware::OverlaySelection& s = *loop.overlaySelection();
        const int overlay = s.choiceFor(id).overlay;
        return overlay < 0 ? "none" : s.name(overlay);
    }
    /// The snapshot of the next frame, copied to `path`.
    void snapshot(const std::string& dir, const std::string& path)
    {
        const auto before = snapshots(dir);
        run("snapshot");
        ASSERT_TRUE(stepUntil([&] { return snapshots(dir).size() > before.size(); }, 10));
        fs::copy_file(snapshots(dir).back(), path, fs::copy_options::overwrite_existing);
    }
    static std::vector<fs::path> snapshots(const std::string& dir)
    {
        std::vector<fs::path> files;
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".png")
                files.push_back(e.path());
        std::sort(files.begin(), files.end());
        return files;
    }
    firmware::FrameLoop loop;
    FakeConsole console;
    std::string command_;
};

class PeopleSnapshots : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!fs::exists(demoModel()))
            GTEST_SKIP() << "out/aam/imm-demo.aam is not built (scripts/dev model)";
        if (!fs::exists(facegen()))
            GTEST_SKIP() << "facegen is not built (tools off)";
        if (!fs::exists(testing_support::sharedData("imm_face_db")))
            GTEST_SKIP() << "no ../shared/data/imm_face_db";
        out_ = testing_support::freshOutputDir("people_snapshots");
        devNull_ = ::open("/dev/null", O_WRONLY);
        firmware::setLogFd(devNull_);
    }
    void TearDown() override
    {
        firmware::setLogFd(2);
        if (devNull_ >= 0)
            ::close(devNull_);
    }
    /// A facegen sequence of `scenario` with the moving faces of `faces`; its folder.
    std::string sequence(const std::string& name, const std::string& scenario,
                         const std::string& faces, int seed)
    {
        const std::string dir = out_ + "/" + name;
        const std::string command =
            facegen() + " --scenario " + scenario + " --faces " + faces + " --seed " +
            std::to_string(seed) + " --frames 90 --size 640x480 --data " +
            testing_support::sharedData("") + " --out " + dir + " >/dev/null";
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        return dir;
    }
    firmware::Config config(const std::string& display)
    {
        firmware::Config c = overlayLoopConfig("people_snapshots_" + display, "glasses");
        c.display.spec = "headless:" + out_ + "/" + display;
        fs::create_directories(out_ + "/" + display);
        c.display.width = 640;  // the camera's 4:3, nothing cropped
        c.display.height = 480;
        c.state.dir = out_ + "/state";
        c.faces.model = demoModel();
        c.overlay.mode = firmware::OverlayConfig::Mode::PerFace;
        c.overlay.initial = "none";
        c.people.enrolFits = 8;
        c.people.enrolTimeoutS = 300;  // the frames decide here, not a slow test machine
        return c;
    }
    /// Enrols the one face of `sequence` as `name`, wearing `overlay` as their own choice.
    void enrol(const std::string& sequence, const std::string& name, const std::string& overlay)
    {
        Mirror m(config("enrol_" + name), sequence);
        ASSERT_TRUE(m.stepUntil([&] { return m.settled(1); }, 300)) << name << " never settled";
        m.run("person add " + name);
        ASSERT_TRUE(m.stepUntil(
            [&] { return m.console.output().find("enrolled " + name) != std::string::npos; }, 300))
            << m.console.output();
        m.run("overlay " + overlay);
        m.stepUntil([] { return false; }, 3);
        EXPECT_NE(m.run("person list").find(name + " (" + overlay), std::string::npos)
            << m.console.output();
    }
    std::string out_;
    int devNull_ = -1;
};

TEST_F(PeopleSnapshots, TwoPeopleWearTheirOwnOverlaysAnnaHasHerBirthdayAndAGuestGetsTheRainHat)
{
    const std::string tom = sequence("tom", "one", "04-1", 3);
    const std::string anna = sequence("anna", "one", "08-1", 4);
    const std::string both = sequence("both", "two", "04-1,08-1", 8);
    const std::string stranger = sequence("stranger", "one", "12-1", 5);
    enrol(tom, "tom", "top_hat");
    enrol(anna, "anna", "glasses");
    const std::string sheet = out_ + "/sheet";
    fs::create_directories(sheet);

    // Both in view after a restart: each recognised, each in their own overlay.
    for (const bool birthday : {false, true}) {
        firmware::Config c = config(birthday ? "birthday" : "own");
        if (birthday)
            c.overlay.precedence = {"birthday", "person", "day", "weather", "global"};
        Mirror m(c, both);
        m.run("person birthday anna " + monthDay(birthday));
        ASSERT_TRUE(m.stepUntil([&] { return m.settled(2); }, 300))
            << "both never settled: " << m.run("faces");
        m.stepUntil([] { return false; }, 3);
        const std::string faces = m.run("faces");
        for (int id : m.shownFaces()) {
            const bool isAnna =
                faces.find("face " + std::to_string(id) + ": person=anna") != std::string::npos;
            const bool isTom =
                faces.find("face " + std::to_string(id) + ": person=tom") != std::string::npos;
            EXPECT_TRUE(isAnna != isTom) << faces;
            EXPECT_EQ(m.wears(id), isAnna ? (birthday ? "birthday_hat" : "glasses") : "top_hat")
                << faces << m.run("status") << m.run("person list");
        }
        m.snapshot(out_ + "/" + (birthday ? "birthday" : "own"),
                   sheet + (birthday ? "/2-anna-birthday.png" : "/1-own-overlays.png"));
    }

    // A stranger on a rainy day: a guest, in the weather's hat.
    firmware::Config c = config("rain");
    const std::string forecast = out_ + "/forecast.json";
    std::ofstream(forecast) << R"({"current":{"weather_code":63}})";
    c.weather.source = "file:" + forecast;
    Mirror m(c, stranger);
    const firmware::OverlaySelection& selection = *m.loop.overlaySelection();
    ASSERT_TRUE(m.stepUntil([&] { return m.settled(1); }, 300));
    // The forecast is read by another thread; the wall clock decides once a second.
    for (int i = 0; i < 400 && selection.automatic(firmware::OverlayRule::Weather) < 0; ++i) {
        ASSERT_TRUE(m.loop.step());
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    m.stepUntil([] { return false; }, 5);
    const int guest = m.shownFaces().at(0);
    const std::string faces = m.run("faces");
    EXPECT_NE(faces.find("face " + std::to_string(guest) + ": person=guest"), std::string::npos)
        << faces;
    EXPECT_EQ(m.wears(guest), "rain_hat") << faces;
    EXPECT_EQ(selection.ruleFor(guest), firmware::OverlayRule::Weather);
    m.snapshot(out_ + "/rain", sheet + "/3-guest-rain.png");
}

}  // namespace
