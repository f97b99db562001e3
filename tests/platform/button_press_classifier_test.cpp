// Timed edge sequences through ButtonPressClassifier::process(), the call GpiodButtonInput::poll()
// makes with the edges it read from libgpiod.

#include "platform/button_press_classifier.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using platform::ButtonEdge;
using platform::ButtonEvent;
using platform::ButtonPressClassifier;
using platform::ButtonPressOptions;

constexpr std::int64_t ms(double v)
{
    return static_cast<std::int64_t>(v * 1'000'000);
}

/// Drives a classifier like a poll loop: edges are queued until the next poll(now).
class Rig {
public:
    explicit Rig(int buttons = 2, ButtonPressOptions options = {}) : c_(buttons, options)
    {
        // Released at start: active-low lines read high.
        for (int b = 1; b <= buttons; ++b)
            c_.setLevel(b, options.activeLow, 0);
    }

    /// A physical level change (press on an active-low line is a falling edge).
    Rig& edge(int button, bool rising, double atMs)
    {
        pending_.push_back({button, rising, ms(atMs)});
        return *this;
    }
    Rig& press(int button, double atMs) { return edge(button, !c_.options().activeLow, atMs); }
    Rig& release(int button, double atMs) { return edge(button, c_.options().activeLow, atMs); }
    /// Contact bounce: `flips` extra level changes 1 ms apart starting at `atMs`, ending on `to`.
    Rig& bounce(int button, double atMs, bool toPressed, int flips)
    {
        for (int i = 0; i < flips; ++i)
            (((flips - i) % 2 == 0) == toPressed) ? press(button, atMs + i)
                                                  : release(button, atMs + i);
        return toPressed ? press(button, atMs + flips) : release(button, atMs + flips);
    }

    /// Delivers the edges that have happened by `nowMs` (as a driver would), then polls.
    std::vector<ButtonEvent> poll(double nowMs)
    {
        std::vector<ButtonEdge> due;
        std::erase_if(pending_, [&](const ButtonEdge& e) {
            if (e.timeNs > ms(nowMs))
                return false;
            due.push_back(e);
            return true;
        });
        ButtonEvent out[ButtonPressClassifier::kQueueCapacity];
        const int n = c_.process(due, ms(nowMs), out, ButtonPressClassifier::kQueueCapacity);
        events_.insert(events_.end(), out, out + n);
        return {out, out + n};
    }
    /// Polls every `stepMs` up to `untilMs`, like the frame loop.
    std::vector<ButtonEvent> pollEvery(double stepMs, double fromMs, double untilMs)
    {
        std::vector<ButtonEvent> all;
        for (double t = fromMs; t <= untilMs; t += stepMs) {
            const auto got = poll(t);
            all.insert(all.end(), got.begin(), got.end());
        }
        return all;
    }

    ButtonPressClassifier& classifier() { return c_; }
    const std::vector<ButtonEvent>& events() const { return events_; }

private:
    ButtonPressClassifier c_;
    std::vector<ButtonEdge> pending_;
    std::vector<ButtonEvent> events_;
};

void expectEvent(const ButtonEvent& e, int button, ButtonEvent::Kind kind, double atMs)
{
    EXPECT_EQ(e.button, button);
    EXPECT_EQ(e.kind, kind) << "button " << button;
    EXPECT_EQ(e.timeNs, ms(atMs)) << "button " << button;
}

TEST(ButtonPressClassifier, CleanShortPressIsReportedOnceTheReleaseIsStable)
{
    Rig rig;
    rig.press(1, 100);
    EXPECT_TRUE(rig.poll(120).empty());  // still debouncing
    EXPECT_FALSE(rig.classifier().pressed(1));
    EXPECT_TRUE(rig.poll(130).empty());
    EXPECT_TRUE(rig.classifier().pressed(1));
    rig.release(1, 300);
    EXPECT_TRUE(rig.poll(329).empty());
    const auto got = rig.poll(330);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Short, 300);
    EXPECT_TRUE(rig.poll(2000).empty());
}

TEST(ButtonPressClassifier, BouncingContactsGiveOneShortPress)
{
    Rig rig;
    rig.bounce(1, 100, true, 7);   // settles pressed at 107
    rig.bounce(1, 250, false, 5);  // settles released at 255
    const auto got = rig.pollEvery(10, 0, 400);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Short, 255);
    EXPECT_GT(rig.classifier().filteredEdges(), 0);
}

TEST(ButtonPressClassifier, BounceDeliveredInOneBatchGivesTheSameResult)
{
    // All edges read in one poll (a slow frame): the timestamps decide, not the poll cadence.
    Rig rig;
    rig.bounce(1, 100, true, 7).bounce(1, 250, false, 5);
    const auto got = rig.poll(400);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Short, 255);
}

TEST(ButtonPressClassifier, SpikesShorterThanTheDebounceAreNoPress)
{
    Rig rig;
    rig.press(1, 100).release(1, 110);    // 10 ms glitch
    rig.press(2, 200).release(2, 229.9);  // just under 30 ms
    EXPECT_TRUE(rig.pollEvery(5, 0, 1500).empty());
    EXPECT_EQ(rig.classifier().filteredEdges(), 2);
}

TEST(ButtonPressClassifier, LongPressFiresWhenTheThresholdPassesWhileHeld)
{
    Rig rig;
    rig.press(1, 100);
    EXPECT_TRUE(rig.poll(899.9).empty());
    const auto got = rig.poll(900);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Long, 900);
    EXPECT_TRUE(rig.classifier().pressed(1));
    rig.release(1, 2500);
    EXPECT_TRUE(rig.pollEvery(10, 910, 3000).empty()) << "the release of a long press is silent";
}

TEST(ButtonPressClassifier, LongPressWithBouncyContactsFiresOnce)
{
    Rig rig;
    rig.bounce(1, 100, true, 9);  // pressed from 109
    // Contact chatter while held (a shaky finger) shorter than the debounce.
    rig.release(1, 500).press(1, 503);
    rig.bounce(1, 1500, false, 6);
    const auto got = rig.pollEvery(16.6, 0, 2000);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Long, 909);
}

TEST(ButtonPressClassifier, ALongHoldSeenOnlyAtItsReleaseIsStillLong)
{
    Rig rig;
    rig.press(1, 0).release(1, 1000);
    const auto got = rig.poll(1100);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Long, 800);
}

TEST(ButtonPressClassifier, AReleaseJustBeforeTheThresholdIsShortEvenIfConfirmedAfterIt)
{
    Rig rig;
    rig.press(1, 0).release(1, 790);
    EXPECT_TRUE(rig.poll(800).empty()) << "the release at 790 is being debounced";
    const auto got = rig.poll(820);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Short, 790);
}

TEST(ButtonPressClassifier, ABounceAcrossTheThresholdDoesNotCancelTheLongPress)
{
    Rig rig;
    rig.press(1, 0).release(1, 790).press(1, 795);
    const auto got = rig.poll(800);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Long, 800);
}

TEST(ButtonPressClassifier, BothButtonsAreIndependent)
{
    Rig rig;
    rig.press(2, 50);                                      // button 2 held long
    rig.press(1, 100).release(1, 250);                     // button 1 short meanwhile
    rig.bounce(1, 400, true, 3).bounce(1, 600, false, 3);  // and again, bouncy
    rig.release(2, 1200);
    const auto got = rig.pollEvery(10, 0, 1500);
    ASSERT_EQ(got.size(), 3u);
    expectEvent(got[0], 1, ButtonEvent::Short, 250);
    expectEvent(got[1], 1, ButtonEvent::Short, 603);
    expectEvent(got[2], 2, ButtonEvent::Long, 850);
}

TEST(ButtonPressClassifier, ActiveHighLinesPressOnTheRisingEdge)
{
    ButtonPressOptions options;
    options.activeLow = false;
    Rig rig(1, options);
    rig.edge(1, true, 100).edge(1, false, 200);
    const auto got = rig.poll(300);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Short, 200);
}

TEST(ButtonPressClassifier, OptionsSetTheDebounceAndTheThreshold)
{
    ButtonPressOptions options;
    options.debounceNs = ms(5);
    options.longPressNs = ms(300);
    Rig rig(1, options);
    rig.press(1, 0).release(1, 10);  // 10 ms: a press with a 5 ms debounce
    rig.press(1, 100).release(1, 450);
    const auto got = rig.pollEvery(1, 0, 500);
    ASSERT_EQ(got.size(), 2u);
    expectEvent(got[0], 1, ButtonEvent::Short, 10);
    expectEvent(got[1], 1, ButtonEvent::Long, 400);
}

TEST(ButtonPressClassifier, ZeroDebounceAcceptsEveryEdge)
{
    ButtonPressOptions options;
    options.debounceNs = 0;
    Rig rig(1, options);
    rig.press(1, 0).release(1, 1).press(1, 2).release(1, 3);
    EXPECT_EQ(rig.poll(3).size(), 2u);
}

TEST(ButtonPressClassifier, AButtonHeldAtStartUpIsIgnoredUntilReleased)
{
    ButtonPressOptions options;
    ButtonPressClassifier c(1, options);
    c.setLevel(1, false, 0);  // active low and low: held (or stuck) at start-up
    ButtonEvent out[4];
    EXPECT_EQ(c.process({}, ms(5000), out, 4), 0) << "no long press for a button held at boot";
    const ButtonEdge release{1, true, ms(6000)};
    EXPECT_EQ(c.process({&release, 1}, ms(7000), out, 4), 0) << "nor a short one at its release";
    const ButtonEdge edges[] = {{1, false, ms(8000)}, {1, true, ms(8100)}};
    ASSERT_EQ(c.process(edges, ms(8200), out, 4), 1);
    expectEvent(out[0], 1, ButtonEvent::Short, 8100);
}

TEST(ButtonPressClassifier, RepeatedEdgesInOneDirectionAreHandled)
{
    // The driver reports the level after an interrupt, so a missed edge shows as two falls.
    Rig rig;
    rig.press(1, 100).press(1, 102).release(1, 300).release(1, 301);
    const auto got = rig.pollEvery(10, 0, 500);
    ASSERT_EQ(got.size(), 1u);
    expectEvent(got[0], 1, ButtonEvent::Short, 301);
}

TEST(ButtonPressClassifier, EdgesOfUnknownButtonsAndBackwardTimesAreSafe)
{
    Rig rig;
    rig.press(0, 10).press(3, 10).press(-1, 10);
    EXPECT_TRUE(rig.poll(100).empty());
    EXPECT_EQ(rig.classifier().ignoredEdges(), 3);
    // Out of order (a clock step): the release is taken as at 200, a zero-length glitch.
    ButtonPressClassifier& c = rig.classifier();
    c.feedEdge({1, false, ms(200)});
    c.feedEdge({1, true, ms(150)});
    EXPECT_TRUE(rig.poll(1500).empty());
    EXPECT_FALSE(c.pressed(1));
}

TEST(ButtonPressClassifier, TakeHandsOutEventsInPieces)
{
    ButtonPressOptions options;
    options.debounceNs = 0;
    ButtonPressClassifier c(1, options);
    c.setLevel(1, true, 0);
    std::vector<ButtonEdge> edges;
    for (int i = 0; i < 5; ++i) {
        edges.push_back({1, false, ms(10 * i)});
        edges.push_back({1, true, ms(10 * i + 5)});
    }
    ButtonEvent out[2];
    EXPECT_EQ(c.process(edges, ms(100), out, 2), 2);
    EXPECT_EQ(out[0].timeNs, ms(5));
    EXPECT_EQ(c.take(out, 2), 2);
    EXPECT_EQ(out[0].timeNs, ms(25));
    EXPECT_EQ(c.take(out, 2), 1);
    EXPECT_EQ(out[0].timeNs, ms(45));
    EXPECT_EQ(c.take(out, 2), 0);
    EXPECT_EQ(c.droppedEvents(), 0);
}

TEST(ButtonPressClassifier, AFullQueueDropsNewerEventsAndCountsThem)
{
    ButtonPressOptions options;
    options.debounceNs = 0;
    ButtonPressClassifier c(1, options);
    c.setLevel(1, true, 0);
    std::vector<ButtonEdge> edges;
    const int presses = ButtonPressClassifier::kQueueCapacity + 5;
    for (int i = 0; i < presses; ++i) {
        edges.push_back({1, false, ms(10 * i)});
        edges.push_back({1, true, ms(10 * i + 5)});
    }
    std::vector<ButtonEvent> out(static_cast<std::size_t>(presses));
    EXPECT_EQ(c.process(edges, ms(10 * presses), out.data(), presses),
              ButtonPressClassifier::kQueueCapacity);
    EXPECT_EQ(c.droppedEvents(), 5);
}

TEST(ButtonPressClassifier, RandomBouncePatternsGiveTheIntendedPresses)
{
    // Presses of random length with random bounce (1-8 flips, 0.2-3 ms apart, shorter than the
    // debounce in total), polled at a random frame cadence: exactly the intended presses.
    std::mt19937 random(1234);
    std::uniform_real_distribution<double> holdMs(60, 1600), gapMs(80, 400), flipMs(0.2, 3);
    std::uniform_int_distribution<int> flipCount(0, 8);
    Rig rig;
    struct Intended {
        int button;
        ButtonEvent::Kind kind;
        double atMs;
    };
    std::vector<Intended> intended;
    double t = 50;
    for (int i = 0; i < 60; ++i) {
        const int button = 1 + i % 2;
        auto bouncy = [&](bool toPressed) {
            const double start = t;
            const int flips = flipCount(random);
            bool level = toPressed;
            for (int f = 0; f < flips; ++f) {
                level ? rig.press(button, t) : rig.release(button, t);
                level = !level;
                t += flipMs(random);
            }
            // The settled edge; the flips before it took < 24 ms, under the 30 ms debounce.
            const double settled = std::max(t, start);
            toPressed ? rig.press(button, settled) : rig.release(button, settled);
            return settled;
        };
        const double pressedAt = bouncy(true);
        t = pressedAt + holdMs(random);
        const double releasedAt = bouncy(false);
        const double held = releasedAt - pressedAt;
        if (held >= 800)
            intended.push_back({button, ButtonEvent::Long, pressedAt + 800});
        else
            intended.push_back({button, ButtonEvent::Short, releasedAt});
        t = releasedAt + gapMs(random);
    }
    std::uniform_real_distribution<double> frameMs(5, 50);
    for (double now = 0; now < t + 100; now += frameMs(random))
        rig.poll(now);
    const auto& got = rig.events();
    ASSERT_EQ(got.size(), intended.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i].button, intended[i].button) << i;
        EXPECT_EQ(got[i].kind, intended[i].kind) << i;
        EXPECT_NEAR(static_cast<double>(got[i].timeNs), static_cast<double>(ms(intended[i].atMs)),
                    1e3)
            << i;
    }
}

TEST(ButtonPressClassifier, ProcessDoesNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    ButtonPressClassifier c(2, {});
    const ButtonEdge edges[] = {{1, false, ms(0)},
                                {1, true, ms(2)},
                                {1, false, ms(3)},
                                {2, false, ms(5)},
                                {1, true, ms(100)}};
    ButtonEvent out[8];
    testing_support::AllocationScope scope;
    c.process(edges, ms(50), out, 8);
    c.process({}, ms(2000), out, 8);
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

TEST(ButtonPressClassifier, RejectsBadCounts)
{
    EXPECT_THROW(ButtonPressClassifier(0, {}), std::invalid_argument);
    EXPECT_THROW(ButtonPressClassifier(ButtonPressClassifier::kMaxButtons + 1, {}),
                 std::invalid_argument);
    ButtonPressOptions negative;
    negative.debounceNs = -1;
    EXPECT_THROW(ButtonPressClassifier(1, negative), std::invalid_argument);
}

}  // namespace
