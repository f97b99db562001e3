// `card train` on the console with no card in view: refused with the numbers, the colour trained
// before stays (in the tracker and in its file); `card forget` returns to untrained and removes
// the file.
#include "fake_console.hpp"
#include "firmware/device_factory.hpp"
#include "firmware/frame_loop.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace {

/// A frame of one colour (with mild noise): the card held up, or a bare wall.
class PaintedSource final : public platform::FrameSource {
public:
    PaintedSource() : image_(160, 120, vision::PixelFormat::RGB24) {}
    const char* description() const noexcept override { return "painted test camera"; }
    vision::Size size() const noexcept override { return {160, 120}; }
    vision::PixelFormat format() const noexcept override { return vision::PixelFormat::RGB24; }
    platform::SourceStatus next(vision::Frame& frame) noexcept override
    {
        const vision::ImageView v = image_.view();
        for (int y = 0; y < v.height; ++y)
            for (int x = 0; x < v.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    const int n = static_cast<int>((x * 7 + y * 13 + c + sequence_) % 5) - 2;
                    v.row(y)[x * 3 + c] = static_cast<std::uint8_t>(colour[c] + n);
                }
        frame.image = image_.view();
        frame.sequence = sequence_++;
        return platform::SourceStatus::Ok;
    }
    int colour[3] = {40, 172, 76};

private:
    vision::ImageBuffer image_;
    std::uint64_t sequence_ = 0;
};

}  // namespace

TEST(CardTraining, NoCardInViewIsRefusedTheOldColourStaysAndForgetUntrains)
{
    firmware::Config config;
    const std::string out = testing_support::freshOutputDir("card_training");
    config.display.spec = "headless:" + out;
    config.display.width = 160;
    config.display.height = 120;
    config.display.snapshotEvery = 0;
    config.faces.enabled = false;
    config.log.summaryIntervalS = 0;
    config.state.dir = testing_support::freshOutputDir("card_training_state");
    const std::string modelPath = config.state.dir + "/card-model.toml";

    auto source = std::make_unique<PaintedSource>();
    PaintedSource* camera = source.get();
    firmware::FrameLoop loop(config, std::move(source), firmware::makeDisplay(config.display));
    FakeConsole console;
    loop.attachConsole(&console);
    auto run = [&](const char* line) {
        console.clearOutput();
        console.type(line);
        for (int i = 0; i < 3; ++i)
            EXPECT_TRUE(loop.step());
        return std::string(console.output());
    };

    std::string reply = run("card train\n");
    ASSERT_NE(reply.find("card: trained"), std::string::npos) << reply;
    const std::string saved = testing_support::readFile(modelPath);
    ASSERT_FALSE(saved.empty());

    camera->colour[0] = 190;  // the card taken away: a pale wall
    camera->colour[1] = 185;
    camera->colour[2] = 170;
    reply = run("card train\n");
    EXPECT_NE(reply.find("card: training refused"), std::string::npos) << reply;
    EXPECT_NE(reply.find("saturation"), std::string::npos) << "in numbers: " << reply;
    EXPECT_NE(reply.find("the previous colour stays"), std::string::npos) << reply;
    EXPECT_EQ(reply.find("card: trained"), std::string::npos) << reply;
    EXPECT_EQ(testing_support::readFile(modelPath), saved) << "the saved colour is kept";
    reply = run("card\n");
    EXPECT_NE(reply.find("colour: r "), std::string::npos) << reply;

    reply = run("card forget\n");
    EXPECT_NE(reply.find("card: colour forgotten"), std::string::npos) << reply;
    EXPECT_FALSE(std::filesystem::exists(modelPath));
    reply = run("card\n");
    EXPECT_NE(reply.find("card: untrained"), std::string::npos) << reply;
    EXPECT_NE(reply.find("colour: not trained"), std::string::npos) << reply;
}
