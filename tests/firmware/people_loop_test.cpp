// The mirror knows people, through the frame loop with the real pipeline and the demo AAM model
// on the FGNet talking face: `person add` is refused without a model, with no face or two faces
// in view, with a bad or taken name; it enrols the one face in view; after a restart (a new
// FrameLoop reading the state folder) the person is recognised and wears their own overlay, and
// on their birthday the birthday overlay; files of another model, corrupt or unreadable are
// skipped at start with one warning each; rename and forget (leaving no trace); the guest button;
// and the loop with a known person in view allocates nothing.
#include "alloc_counter.hpp"
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
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

std::string demoModel()
{
    return testing_support::sourceDir() + "/out/aam/imm-demo.aam";
}

/// The talking face twice, side by side (the second a few frames behind): two faces in view.
class TwoFaceSource final : public platform::FrameSource {
public:
    TwoFaceSource() : one_(30)
    {
        vision::Frame f;
        one_.next(f);
        const vision::ConstImageView v = f.image;
        buffer_ = vision::ImageBuffer(2 * v.width, v.height, v.format);
        for (int i = 0; i < 7; ++i)
            two_.next(f);
    }
    const char* description() const noexcept override { return "two talking faces"; }
    vision::Size size() const noexcept override
    {
        return {buffer_.view().width, buffer_.view().height};
    }
    vision::PixelFormat format() const noexcept override { return buffer_.view().format; }
    platform::SourceStatus next(vision::Frame& frame) noexcept override
    {
        vision::Frame a, b;
        one_.next(a);
        two_.next(b);
        const vision::ImageView out = buffer_.view();
        const std::size_t row = static_cast<std::size_t>(a.image.width) *
                                static_cast<std::size_t>(vision::bytesPerPixel(out.format));
        for (int y = 0; y < out.height; ++y) {
            std::uint8_t* dst = out.data + static_cast<std::ptrdiff_t>(y) * out.stride;
            std::memcpy(dst, a.image.data + static_cast<std::ptrdiff_t>(y) * a.image.stride, row);
            std::memcpy(dst + row, b.image.data + static_cast<std::ptrdiff_t>(y) * b.image.stride,
                        row);
        }
        frame.image = buffer_.view();
        frame.sequence = a.sequence;
        frame.timestampNs = a.timestampNs;
        return platform::SourceStatus::Ok;
    }

private:
    PreloadedFaceSource one_;
    PreloadedFaceSource two_{30};
    vision::ImageBuffer buffer_;
};

/// Buttons whose presses the test schedules (one poll per frame).
class ScriptedButtons final : public platform::ButtonInput {
public:
    const char* description() const noexcept override { return "scripted test buttons"; }
    int buttonCount() const noexcept override { return 3; }
    int poll(platform::ButtonEvent* out, int capacity) noexcept override
    {
        if (capacity < 1 || pending_.button == 0)
            return 0;
        out[0] = pending_;
        pending_ = {};
        return 1;
    }
    int readPressed(bool* out, int capacity) noexcept override
    {
        for (int i = 0; i < capacity && i < 3; ++i)
            out[i] = false;
        return 3;
    }
    void press(int button, platform::ButtonEvent::Kind kind) { pending_ = {button, kind, 0}; }

private:
    platform::ButtonEvent pending_{};
};

firmware::Config peopleConfig(const std::string& name, bool model = true)
{
    firmware::Config config = overlayLoopConfig(name, "glasses");
    config.faces.model = model ? demoModel() : "";
    config.overlay.mode = firmware::OverlayConfig::Mode::PerFace;
    config.people.enrolFits = 8;
    config.people.enrolTimeoutS = 120;  // the frames decide here, not a slow test machine
    std::filesystem::remove_all(config.state.dir);
    return config;
}

/// A frame loop with `config` on `source` (default: the talking face), the console attached.
struct Mirror {
    explicit Mirror(const firmware::Config& config,
                    std::unique_ptr<platform::FrameSource> source = nullptr)
        : loop(config, source ? std::move(source) : std::make_unique<PreloadedFaceSource>(30),
               firmware::makeDisplay(config.display))
    {
        loop.attachConsole(&console);
    }
    /// Types `line` and runs one frame; what the console printed since.
    std::string run(const std::string& line)
    {
        console.clearOutput();
        command_ = line + "\n";
        console.type(command_.c_str());
        EXPECT_TRUE(loop.step());
        return std::string(console.output());
    }
    /// Frames until `done` (at most `frames`); whether it came.
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
    int shownFace() const
    {
        for (const vision::TrackedFace& f : loop.lastFrameState().faces)
            if (f.shown())
                return f.id;
        return 0;
    }
    /// The face is shown and its signature settled (recognition has decided).
    bool settled() const
    {
        const int id = shownFace();
        const vision::FaceFit* fit = vision::fitFor(loop.lastFrameState().fits, id);
        return id != 0 && fit && fit->signatureSettled;
    }
    bool printed(const std::string& text) const
    {
        return console.output().find(text) != std::string_view::npos;
    }
    firmware::FrameLoop loop;
    FakeConsole console;
    std::string command_;
};

class PeopleLoop : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!std::filesystem::exists(demoModel()))
            GTEST_SKIP() << "out/aam/imm-demo.aam is not built (scripts/dev model)";
        devNull_ = ::open("/dev/null", O_WRONLY);
        firmware::setLogFd(devNull_);
    }
    void TearDown() override
    {
        firmware::setLogFd(2);
        if (devNull_ >= 0)
            ::close(devNull_);
    }
    /// Enrols the talking face as `name` in `m`; the console's lines.
    std::string enrol(Mirror& m, const std::string& name)
    {
        EXPECT_TRUE(m.stepUntil([&] { return m.settled(); }, 200)) << "the signature never settled";
        std::string out = m.run("person add " + name);
        EXPECT_NE(out.find("person add " + name + ": collecting 8 fits"), std::string::npos) << out;
        EXPECT_TRUE(m.stepUntil([&] { return m.printed("enrolled " + name); }, 200))
            << m.console.output();
        return std::string(m.console.output());
    }
    int devNull_ = -1;
};

TEST_F(PeopleLoop, EnrolmentIsRefusedWithoutAModelWithNoFaceOrTwoFacesAndBadNames)
{
    {
        Mirror m(peopleConfig("people_no_model", false));
        m.stepUntil([&] { return m.shownFace() != 0; }, 60);
        EXPECT_NE(m.run("person add anna").find("error: no AAM model"), std::string::npos)
            << m.console.output();
    }
    {
        Mirror m(peopleConfig("people_refused"));
        ASSERT_TRUE(m.loop.step());
        EXPECT_NE(m.run("person add anna").find("error: person add: no face in view"),
                  std::string::npos)
            << m.console.output();
        EXPECT_NE(m.run("person add").find("error: expected person add NAME; usage: person ["),
                  std::string::npos)
            << m.console.output();
        EXPECT_NE(m.run("person birthday x").find("error: expected person birthday NAME MM-DD"),
                  std::string::npos)
            << m.console.output();
        ASSERT_TRUE(m.stepUntil([&] { return m.shownFace() != 0; }, 60));
        for (const char* bad : {"person add ../etc", "person add guest", "person add -x",
                                "person add abcdefghijklmnopqrstuvwxyz0123456789"})
            EXPECT_NE(m.run(bad).find("error: person add: '"), std::string::npos)
                << bad << ": " << m.console.output();
    }
    {
        firmware::Config config = peopleConfig("people_two_faces");
        Mirror m(config, std::make_unique<TwoFaceSource>());
        int shown = 0;
        m.stepUntil(
            [&] {
                shown = 0;
                for (const vision::TrackedFace& f : m.loop.lastFrameState().faces)
                    shown += f.shown();
                return shown == 2;
            },
            120);
        ASSERT_EQ(shown, 2) << "both talking faces should be shown";
        EXPECT_NE(m.run("person add anna").find("error: person add: several faces in view"),
                  std::string::npos)
            << m.console.output();
        EXPECT_FALSE(std::filesystem::exists(config.state.dir + "/people/anna.toml"));
    }
}

TEST_F(PeopleLoop, AKeptPersonIsRecognisedAfterARestartWithTheirOverlayAndBirthday)
{
    const firmware::Config config = peopleConfig("people_restart");
    const std::string file = config.state.dir + "/people/anna.toml";
    {
        Mirror m(config);
        const std::string out = enrol(m, "anna");
        EXPECT_NE(out.find("enrolled anna from "), std::string::npos) << out;
        ASSERT_TRUE(std::filesystem::exists(file));
        struct stat st {};
        ASSERT_EQ(::stat(file.c_str(), &st), 0);
        EXPECT_EQ(st.st_mode & 0777, 0600u) << "only the service reads who it knows";
        EXPECT_NE(m.run("person add anna").find("is taken"), std::string::npos)
            << m.console.output();
        // Her choice on screen (per_face: the face being changed) is kept in her file.
        m.run("overlay sunglasses");
        m.stepUntil([] { return false; }, 3);
        EXPECT_NE(m.run("faces").find("person=anna score="), std::string::npos)
            << m.console.output();
    }
    {
        Mirror m(config);
        ASSERT_TRUE(m.stepUntil([&] { return m.settled(); }, 200));
        ASSERT_TRUE(m.loop.step());
        const int face = m.shownFace();
        const std::string faces = m.run("faces");
        EXPECT_NE(faces.find("face " + std::to_string(face) + ": person=anna score="),
                  std::string::npos)
            << faces;
        const firmware::OverlaySelection& selection = *m.loop.overlaySelection();
        EXPECT_STREQ(selection.name(selection.choiceFor(face).overlay), "sunglasses");
        EXPECT_EQ(selection.ruleFor(face), firmware::OverlayRule::Person);
        const std::string status = m.run("status");
        EXPECT_NE(status.find("by person"), std::string::npos) << status;
        EXPECT_NE(status.find("people: 1 known"), std::string::npos) << status;
        const std::string json = m.run("status --json");
        EXPECT_NE(json.find("\"people\":{\"known\":1,\"faces\":[{\"id\":" + std::to_string(face) +
                            ",\"person\":\"anna\",\"score\":"),
                  std::string::npos)
            << json;

        // Her birthday: the person rule (her own overlay) comes first; without one, the birthday.
        EXPECT_NE(m.run("person birthday anna " + todayMonthDay())
                      .find("anna's birthday is " + todayMonthDay()),
                  std::string::npos)
            << m.console.output();
        m.run("overlay none");  // her own choice now: none; the person rule still wins
        EXPECT_NE(m.run("person list").find("anna (none, birthday " + todayMonthDay() + ")"),
                  std::string::npos)
            << m.console.output();
    }
    {
        // Her kept choice taken away in the file: the birthday rule puts the crown on her alone.
        std::string text;
        {
            std::FILE* f = std::fopen(file.c_str(), "r");
            ASSERT_NE(f, nullptr);
            char buffer[8192];
            text.assign(buffer, std::fread(buffer, 1, sizeof buffer, f));
            std::fclose(f);
        }
        const std::size_t at = text.find("overlay = ");
        ASSERT_NE(at, std::string::npos) << text;
        text.erase(at, text.find('\n', at) + 1 - at);
        std::FILE* f = std::fopen(file.c_str(), "w");
        std::fwrite(text.data(), 1, text.size(), f);
        std::fclose(f);
        Mirror m(config);
        ASSERT_TRUE(m.stepUntil([&] { return m.settled(); }, 200));
        for (int i = 0; i < 3; ++i)
            ASSERT_TRUE(m.loop.step());
        const int face = m.shownFace();
        const firmware::OverlaySelection& selection = *m.loop.overlaySelection();
        EXPECT_STREQ(selection.name(selection.choiceFor(face).overlay), "birthday_hat");
        EXPECT_EQ(selection.ruleFor(face), firmware::OverlayRule::Birthday);
        EXPECT_NE(m.run("status").find("by birthday"), std::string::npos) << m.console.output();
    }
}

TEST_F(PeopleLoop, FilesOfAnotherModelCorruptOrUnreadableAreSkippedAtStartWithAWarningEach)
{
    const firmware::Config config = peopleConfig("people_skipped");
    const std::string dir = config.state.dir + "/people/";
    {
        Mirror m(config);
        enrol(m, "anna");
    }
    std::filesystem::copy_file(dir + "anna.toml", dir + "other.toml");
    {
        std::FILE* f = std::fopen((dir + "foreign.toml").c_str(), "w");
        std::fputs("name = \"foreign\"\nmodel = \"crc32:00000000\"\nsamples = 1\n", f);
        std::fclose(f);
        f = std::fopen((dir + "broken.toml").c_str(), "w");
        std::fputs("name = \"broken\"\nshape = [", f);
        std::fclose(f);
    }
    ASSERT_EQ(::mkfifo((dir + "fifo.toml").c_str(), 0600), 0);
    Mirror m(config);
    std::vector<std::string> warnings;
    firmware::forEachRecentLogLine(
        firmware::kLogRingLines,
        [](const char* line, void* context) {
            static_cast<std::vector<std::string>*>(context)->emplace_back(line);
        },
        &warnings, firmware::LogLevel::Warn);
    for (const char* name : {"other", "foreign", "broken", "fifo"}) {
        int lines = 0;
        for (const std::string& w : warnings)
            lines += w.find(dir + name + ".toml") != std::string::npos;
        EXPECT_EQ(lines, 1) << name << ": one warning naming it";
    }
    EXPECT_NE(m.run("person list").find("people: 1 known: anna"), std::string::npos)
        << m.console.output();
    ASSERT_TRUE(m.stepUntil([&] { return m.settled(); }, 200));
    ASSERT_TRUE(m.loop.step());
    EXPECT_NE(m.run("faces").find("person=anna"), std::string::npos) << m.console.output();
}

TEST_F(PeopleLoop, RenameAndForgetLeaveNoTrace)
{
    const firmware::Config config = peopleConfig("people_forget");
    const std::string dir = config.state.dir + "/people/";
    {
        Mirror m(config);
        enrol(m, "anna");
        EXPECT_NE(m.run("person rename anna annie").find("person: anna is now annie"),
                  std::string::npos)
            << m.console.output();
        EXPECT_FALSE(std::filesystem::exists(dir + "anna.toml"));
        EXPECT_TRUE(std::filesystem::exists(dir + "annie.toml"));
        EXPECT_NE(m.run("person rename annie ../x").find("error: person rename: '"),
                  std::string::npos);
        EXPECT_NE(m.run("person rename bob x").find("nobody called 'bob'"), std::string::npos);
        EXPECT_NE(m.run("person list").find("people: 1 known: annie"), std::string::npos)
            << m.console.output();
        m.run("person birthday annie 02-29");
        EXPECT_NE(m.run("person forget annie").find("person: forgot annie"), std::string::npos)
            << m.console.output();
        EXPECT_FALSE(std::filesystem::exists(dir + "annie.toml"));
        const std::string status = m.run("status");
        EXPECT_EQ(status.find("annie"), std::string::npos) << status;
        EXPECT_NE(status.find("people: 0 known"), std::string::npos) << status;
        EXPECT_EQ(m.run("faces").find("annie"), std::string::npos) << m.console.output();
    }
    {
        Mirror m(config);
        ASSERT_TRUE(m.stepUntil([&] { return m.settled(); }, 200));
        ASSERT_TRUE(m.loop.step());
        const std::string faces = m.run("faces");
        EXPECT_NE(faces.find("person=guest"), std::string::npos) << faces;
        EXPECT_EQ(faces.find("annie"), std::string::npos) << faces;
        enrol(m, "bob");
        std::FILE* stray = std::fopen((dir + "other.toml").c_str(), "w");
        std::fputs("name = \"other\"\n", stray);
        std::fclose(stray);
        EXPECT_NE(m.run("person forget --all").find("person: forgot everyone (2 files removed)"),
                  std::string::npos)
            << m.console.output();
        EXPECT_TRUE(std::filesystem::is_empty(dir));
    }
}

TEST_F(PeopleLoop, TheGuestButtonEnrolsTheNearestFaceAsTheNextGuest)
{
    const firmware::Config config = peopleConfig("people_guest");
    Mirror m(config);
    auto buttons = std::make_unique<ScriptedButtons>();
    ScriptedButtons* b = buttons.get();
    m.loop.attachButtons(std::move(buttons));
    ASSERT_TRUE(m.stepUntil([&] { return m.settled(); }, 200));
    b->press(3, platform::ButtonEvent::Long);  // the default map: long 3 = enrol-guest
    ASSERT_TRUE(m.stepUntil([&] { return m.printed("enrolled guest-1"); }, 200))
        << m.console.output();
    EXPECT_TRUE(std::filesystem::exists(config.state.dir + "/people/guest-1.toml"));
    EXPECT_NE(m.run("faces").find("person=guest-1 score="), std::string::npos)
        << m.console.output();
}

TEST_F(PeopleLoop, TheLoopWithAKnownPersonInViewAllocatesNothing)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    const firmware::Config config = peopleConfig("people_alloc");
    {
        Mirror m(config);
        enrol(m, "anna");
    }
    Mirror m(config);
    ASSERT_TRUE(m.stepUntil([&] { return m.settled(); }, 200));
    testing_support::AllocationCounts counts;
    {
        testing_support::AllocationScope scope;
        for (int i = 0; i < 100; ++i) {
            if (i % 25 == 5)
                m.console.type(i % 50 == 5 ? "faces\nperson list\n" : "status\n");
            ASSERT_TRUE(m.loop.step());
        }
        counts = scope.counts();
    }
    EXPECT_NE(m.console.output().find("person=anna"), std::string_view::npos) << m.console.output();
    EXPECT_EQ(counts.cxxNew, 0);
    EXPECT_EQ(counts.ownMalloc, 0);
}

}  // namespace
