#include "firmware/overlay_selection.hpp"

#include "alloc_counter.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace {

using firmware::OverlayChange;
using firmware::OverlayChoice;
using firmware::OverlayMode;
using firmware::OverlaySelection;
using firmware::OverlaySelectionOptions;

constexpr std::int64_t ms(double v)
{
    return static_cast<std::int64_t>(v * 1'000'000);
}

std::vector<std::string> catalogue()
{
    return {"glasses", "sunglasses", "top-hat", "graduation-cap"};
}

vision::TrackedFace face(int id, float size, vision::FaceState state = vision::FaceState::Confirmed)
{
    vision::TrackedFace f;
    f.id = id;
    f.centre = {100.f * static_cast<float>(id), 200.f};
    f.size = size;
    f.state = state;
    return f;
}

OverlaySelectionOptions options(OverlayMode mode, int maxFaces = 8)
{
    OverlaySelectionOptions o;
    o.mode = mode;
    o.maxFaces = maxFaces;
    return o;
}

TEST(OverlaySelection, NamesAndLookUp)
{
    OverlaySelection s(catalogue(), {});
    EXPECT_EQ(s.size(), 4);
    EXPECT_STREQ(s.name(2), "top-hat");
    EXPECT_STREQ(s.name(-1), "none");
    EXPECT_STREQ(s.name(4), "none");
    EXPECT_EQ(s.find("graduation-cap"), 3);
    EXPECT_EQ(s.find("crown"), -1);
    EXPECT_EQ(s.selected(), -1);
    EXPECT_EQ(OverlaySelection(catalogue(), {}, 1).selected(), 1);
    EXPECT_EQ(OverlaySelection(catalogue(), {}, 9).selected(), -1) << "out of range: none";
}

TEST(OverlaySelection, NextAndPrevCycleThroughNone)
{
    OverlaySelection s(catalogue(), {});
    std::vector<int> seen;
    for (int i = 0; i < 6; ++i)
        seen.push_back(s.next().overlay);
    EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, -1, 0}));
    EXPECT_EQ(s.prev().overlay, -1);
    EXPECT_EQ(s.prev().overlay, 3);
    EXPECT_EQ(s.selected(), 3);
}

TEST(OverlaySelection, SelectByNameOffAndGeneration)
{
    OverlaySelection s(catalogue(), {});
    const auto g0 = s.generation();
    OverlayChange change;
    ASSERT_TRUE(s.select("top-hat", &change));
    EXPECT_EQ(change.overlay, 2);
    EXPECT_EQ(change.faceId, 0);
    EXPECT_NE(s.generation(), g0);
    const auto g1 = s.generation();
    EXPECT_TRUE(s.select("top-hat"));
    EXPECT_EQ(s.generation(), g1) << "no change, nothing to save";
    EXPECT_FALSE(s.select("crown"));
    EXPECT_FALSE(s.select(7));
    EXPECT_EQ(s.selected(), 2);
    EXPECT_EQ(s.off().overlay, -1);
    EXPECT_EQ(s.selected(), -1);
    EXPECT_TRUE(s.select("sunglasses"));
    EXPECT_TRUE(s.select("none"));
    EXPECT_EQ(s.selected(), -1);
    s.setMode(OverlayMode::PerFace);
    EXPECT_NE(s.generation(), g1);
}

TEST(OverlaySelection, OnlyShownFacesWearOverlaysAndTheyFadeIn)
{
    OverlaySelection s(catalogue(), {}, 2);
    const vision::TrackedFace tentative[] = {face(1, 80, vision::FaceState::Tentative)};
    s.update(tentative, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, -1);

    const vision::TrackedFace confirmed[] = {face(1, 80)};
    s.update(confirmed, ms(10));
    EXPECT_EQ(s.choiceFor(1).overlay, 2);
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 0.f) << "the first frame is invisible";
    s.update(confirmed, ms(135));
    EXPECT_NEAR(s.choiceFor(1).alpha, 0.5f, 1e-5);
    s.update(confirmed, ms(260));
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 1.f);
    s.update(confirmed, ms(400));
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 1.f);

    // Missing (within the tracker's grace) keeps its overlay.
    const vision::TrackedFace missing[] = {face(1, 80, vision::FaceState::Missing)};
    s.update(missing, ms(433));
    EXPECT_EQ(s.choiceFor(1).overlay, 2);
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 1.f);

    // Dropped: forgotten at once (no pose left to draw on).
    s.update({}, ms(466));
    EXPECT_EQ(s.choiceFor(1).overlay, -1);
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 0.f);
}

TEST(OverlaySelection, ASwitchFadesOutAndInWithinTheFadeTime)
{
    OverlaySelection s(catalogue(), {}, 0);
    const vision::TrackedFace faces[] = {face(1, 80)};
    s.update(faces, ms(0));
    s.update(faces, ms(300));
    ASSERT_FLOAT_EQ(s.choiceFor(1).alpha, 1.f);
    s.next();
    s.update(faces, ms(362.5));
    EXPECT_EQ(s.choiceFor(1).overlay, 0) << "the old one fades out first";
    EXPECT_NEAR(s.choiceFor(1).alpha, 0.5f, 1e-5);
    s.update(faces, ms(425));
    EXPECT_EQ(s.choiceFor(1).overlay, 1);
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 0.f);
    s.update(faces, ms(487.5));
    EXPECT_NEAR(s.choiceFor(1).alpha, 0.5f, 1e-5);
    s.update(faces, ms(550));
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 1.f);

    // Off fades out at the normal rate.
    s.off();
    s.update(faces, ms(675));
    EXPECT_EQ(s.choiceFor(1).overlay, 1);
    EXPECT_NEAR(s.choiceFor(1).alpha, 0.5f, 1e-5);
    s.update(faces, ms(800));
    EXPECT_EQ(s.choiceFor(1).overlay, -1);
}

TEST(OverlaySelection, ZeroFadeIsInstant)
{
    OverlaySelectionOptions o;
    o.fadeNs = 0;
    OverlaySelection s(catalogue(), o, 1);
    const vision::TrackedFace faces[] = {face(1, 80)};
    s.update(faces, ms(0));
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 1.f);
    s.next();
    s.update(faces, ms(66));
    EXPECT_EQ(s.choiceFor(1).overlay, 2);
    EXPECT_FLOAT_EQ(s.choiceFor(1).alpha, 1.f);
}

TEST(OverlaySelection, GlobalModeDressesEveryoneAlike)
{
    OverlaySelection s(catalogue(), options(OverlayMode::Global), 1);
    const vision::TrackedFace faces[] = {face(1, 80), face(2, 120)};
    s.update(faces, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, 1);
    EXPECT_EQ(s.choiceFor(2).overlay, 1);
    EXPECT_EQ(s.next().faceId, 0);
    EXPECT_EQ(s.targetFace(), 0);
    s.update(faces, ms(1000));
    EXPECT_EQ(s.choiceFor(1).overlay, 2);
    EXPECT_EQ(s.choiceFor(2).overlay, 2);
}

TEST(OverlaySelection, PerFaceGivesNewFacesDifferentOverlays)
{
    OverlaySelection s(catalogue(), options(OverlayMode::PerFace), 2);
    const vision::TrackedFace one[] = {face(1, 80)};
    s.update(one, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, 2);
    const vision::TrackedFace two[] = {face(1, 80), face(2, 60), face(3, 70)};
    s.update(two, ms(33));
    EXPECT_EQ(s.choiceFor(2).overlay, 3);
    EXPECT_EQ(s.choiceFor(3).overlay, 0) << "wraps round the catalogue";
}

TEST(OverlaySelection, PerFaceButtonsActOnTheLargestFace)
{
    OverlaySelection s(catalogue(), options(OverlayMode::PerFace), 0);
    const vision::TrackedFace first[] = {face(1, 80), face(2, 150)};
    s.update(first, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, 0);
    EXPECT_EQ(s.choiceFor(2).overlay, 1);
    EXPECT_EQ(s.targetFace(), 2);
    const OverlayChange change = s.next();
    EXPECT_EQ(change.faceId, 2);
    EXPECT_EQ(change.overlay, 2);
    EXPECT_EQ(s.selected(), 2) << "the last choice is what new faces start with";
    s.update(first, ms(1000));
    EXPECT_EQ(s.choiceFor(1).overlay, 0) << "the other face keeps its own";
    EXPECT_EQ(s.choiceFor(2).overlay, 2);

    // Face 1 steps closer: now it is the target.
    const vision::TrackedFace closer[] = {face(1, 200), face(2, 150)};
    s.update(closer, ms(1033));
    EXPECT_EQ(s.targetFace(), 1);
    OverlayChange byName;
    ASSERT_TRUE(s.select("graduation-cap", &byName));
    EXPECT_EQ(byName.faceId, 1);
    s.update(closer, ms(2000));
    EXPECT_EQ(s.choiceFor(1).overlay, 3);
    EXPECT_EQ(s.choiceFor(2).overlay, 2);
}

TEST(OverlaySelection, PerFaceTiesGoToTheFaceShownLongest)
{
    OverlaySelection s(catalogue(), options(OverlayMode::PerFace), 0);
    const vision::TrackedFace a[] = {face(5, 100)};
    s.update(a, ms(0));
    const vision::TrackedFace both[] = {face(5, 100), face(6, 105)};  // within 10%
    s.update(both, ms(33));
    EXPECT_EQ(s.targetFace(), 5);
    const vision::TrackedFace bigger[] = {face(5, 100), face(6, 115)};
    s.update(bigger, ms(66));
    EXPECT_EQ(s.targetFace(), 6);
}

TEST(OverlaySelection, PerFaceWithNobodyChangesWhatTheNextFaceGets)
{
    OverlaySelection s(catalogue(), options(OverlayMode::PerFace), 0);
    const OverlayChange change = s.next();
    EXPECT_EQ(change.faceId, 0);
    EXPECT_EQ(change.overlay, 1);
    const vision::TrackedFace one[] = {face(9, 80)};
    s.update(one, ms(0));
    EXPECT_EQ(s.choiceFor(9).overlay, 1);
}

TEST(OverlaySelection, OffTurnsEveryFaceOffInPerFaceMode)
{
    OverlaySelection s(catalogue(), options(OverlayMode::PerFace), 0);
    const vision::TrackedFace faces[] = {face(1, 80), face(2, 90)};
    s.update(faces, ms(0));
    s.off();
    s.update(faces, ms(1000));
    EXPECT_EQ(s.choiceFor(1).overlay, -1);
    EXPECT_EQ(s.choiceFor(2).overlay, -1);
    const vision::TrackedFace newcomer[] = {face(1, 80), face(2, 90), face(3, 70)};
    s.update(newcomer, ms(1033));
    EXPECT_EQ(s.choiceFor(3).overlay, -1);
}

TEST(OverlaySelection, SwitchingToGlobalUnifiesTheFaces)
{
    OverlaySelection s(catalogue(), options(OverlayMode::PerFace), 0);
    const vision::TrackedFace faces[] = {face(1, 80), face(2, 90)};
    s.update(faces, ms(0));
    ASSERT_NE(s.choiceFor(1).overlay, s.choiceFor(2).overlay);
    s.setMode(OverlayMode::Global);
    s.update(faces, ms(1000));
    EXPECT_EQ(s.choiceFor(1).overlay, 0);
    EXPECT_EQ(s.choiceFor(2).overlay, 0);
}

TEST(OverlaySelection, FacesBeyondCapacityWearNothingUntilASlotFrees)
{
    OverlaySelection s(catalogue(), options(OverlayMode::Global, 2), 0);
    const vision::TrackedFace three[] = {face(1, 80), face(2, 80), face(3, 80)};
    s.update(three, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, 0);
    EXPECT_EQ(s.choiceFor(2).overlay, 0);
    EXPECT_EQ(s.choiceFor(3).overlay, -1);
    const vision::TrackedFace later[] = {face(2, 80), face(3, 80)};
    s.update(later, ms(33));
    EXPECT_EQ(s.choiceFor(3).overlay, 0);
}

TEST(OverlaySelection, AnEmptyCatalogueSelectsNothing)
{
    OverlaySelection s({}, {});
    EXPECT_EQ(s.next().overlay, -1);
    EXPECT_EQ(s.prev().overlay, -1);
    const vision::TrackedFace faces[] = {face(1, 80)};
    s.update(faces, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, -1);
}

TEST(OverlaySelection, RejectsBadCataloguesAndOptions)
{
    EXPECT_THROW(OverlaySelection({"a", "b", "a"}, {}), std::invalid_argument);
    EXPECT_THROW(OverlaySelection({"a", ""}, {}), std::invalid_argument);
    EXPECT_THROW(OverlaySelection({"none"}, {}), std::invalid_argument);
    EXPECT_THROW(OverlaySelection({"a"}, options(OverlayMode::Global, 0)), std::invalid_argument);
    OverlaySelectionOptions negative;
    negative.fadeNs = -1;
    EXPECT_THROW(OverlaySelection({"a"}, negative), std::invalid_argument);
}

TEST(OverlaySelection, ModeWords)
{
    OverlayMode mode{};
    ASSERT_TRUE(firmware::parseOverlayMode("per_face", mode));
    EXPECT_EQ(mode, OverlayMode::PerFace);
    EXPECT_STREQ(firmware::toString(mode), "per_face");
    ASSERT_TRUE(firmware::parseOverlayMode("global", mode));
    EXPECT_STREQ(firmware::toString(mode), "global");
    EXPECT_FALSE(firmware::parseOverlayMode("per-face", mode));
}

TEST(OverlaySelection, FramesAndActionsDoNotAllocate)
{
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation hooks are not compiled in sanitizer builds";
    OverlaySelection s(catalogue(), options(OverlayMode::PerFace), 0);
    const vision::TrackedFace faces[] = {face(1, 80), face(2, 90), face(3, 70)};
    testing_support::AllocationScope scope;
    float sum = 0.f;
    for (int frame = 0; frame < 100; ++frame) {
        s.update(faces, ms(33.3 * frame));
        for (const auto& f : faces)
            sum += s.choiceFor(f.id).alpha;
        if (frame % 10 == 0)
            s.next();
        if (frame == 50)
            s.select("top-hat");
    }
    s.update({}, ms(5000));
    EXPECT_GT(sum, 0.f);
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
}

}  // namespace

// The automatic rules (firmware/overlay_rules.hpp): the day's and the weather's overlays go on
// faces nobody chose for; a button press is the choice of the faces on screen; the order is the
// configured precedence.
TEST(OverlaySelectionRules, TheDayAndTheWeatherDressNewFacesAndAButtonPressStillWins)
{
    OverlaySelectionOptions o = options(OverlayMode::Global);
    o.fadeNs = 0;
    OverlaySelection s(catalogue(), o, 0);  // glasses for everyone
    s.setAutomatic(firmware::OverlayRule::Weather, 1);  // sunglasses: a sunny day
    const std::vector<vision::TrackedFace> one{face(1, 100.f)};
    s.update(one, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, 1);
    EXPECT_EQ(s.ruleFor(1), firmware::OverlayRule::Weather);

    s.setAutomatic(firmware::OverlayRule::Day, 3);  // a holiday beats the weather
    s.update(one, ms(40));
    EXPECT_EQ(s.choiceFor(1).overlay, 3);
    EXPECT_EQ(s.ruleFor(1), firmware::OverlayRule::Day);

    s.next();  // the person in front presses the button: their own choice from now on
    s.update(one, ms(80));
    EXPECT_EQ(s.choiceFor(1).overlay, 1) << "next after glasses";
    EXPECT_EQ(s.ruleFor(1), firmware::OverlayRule::Person);

    const std::vector<vision::TrackedFace> two{face(1, 100.f), face(2, 90.f)};
    s.update(two, ms(120));
    EXPECT_EQ(s.choiceFor(2).overlay, 3) << "a newcomer gets the day's";
    EXPECT_EQ(s.choiceFor(1).overlay, 1);

    s.setAutomatic(firmware::OverlayRule::Day, -1);  // the holiday is over
    s.setAutomatic(firmware::OverlayRule::Weather, -1);  // no forecast
    s.update(two, ms(160));
    EXPECT_EQ(s.choiceFor(2).overlay, 1) << "the global choice";
    EXPECT_EQ(s.ruleFor(2), firmware::OverlayRule::Global);

    s.off();  // "none" is a choice too
    s.setAutomatic(firmware::OverlayRule::Day, 3);
    s.update(two, ms(200));
    EXPECT_EQ(s.choiceFor(1).overlay, -1);
    EXPECT_EQ(s.choiceFor(2).overlay, -1);
    s.setAutomatic(firmware::OverlayRule::Day, 7);  // out of range: ignored
    EXPECT_EQ(s.automatic(firmware::OverlayRule::Day), 3);
}

TEST(OverlaySelectionRules, ThePrecedenceIsConfigurable)
{
    firmware::OverlayPrecedence order{};
    std::string problem;
    const std::vector<std::string> words{"global", "person", "weather", "day", "birthday"};
    ASSERT_TRUE(firmware::parseOverlayPrecedence(words, order, problem)) << problem;
    OverlaySelectionOptions o = options(OverlayMode::Global);
    o.fadeNs = 0;
    o.precedence = order;
    OverlaySelection s(catalogue(), o, 2);
    s.setAutomatic(firmware::OverlayRule::Day, 3);
    s.setAutomatic(firmware::OverlayRule::Weather, 1);
    const std::vector<vision::TrackedFace> one{face(1, 100.f)};
    s.update(one, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, 2) << "the global choice first";
    s.off();
    s.update(one, ms(40));
    EXPECT_EQ(s.choiceFor(1).overlay, -1) << "the person's none, before the weather";
    s.update({}, ms(80));
    s.update(one, ms(120));  // a new track: no own choice, global none offers nothing
    EXPECT_EQ(s.choiceFor(1).overlay, 1) << "then the weather, before the day";

    const std::pair<std::vector<std::string>, const char*> bad[] = {
        {{"person", "day"}, "must name each of"},
        {{"person", "birthday", "day", "weather", "moon"}, "'moon' is not one of"},
        {{"person", "birthday", "day", "weather", "day"}, "names 'day' twice"},
    };
    for (const auto& [w, why] : bad) {
        EXPECT_FALSE(firmware::parseOverlayPrecedence(w, order, problem));
        EXPECT_NE(problem.find(why), std::string::npos) << problem;
    }
}

TEST(OverlaySelectionRules, AKeptChoiceIsThePersonsAndTheBirthdayIsTheirsAlone)
{
    OverlaySelectionOptions o = options(OverlayMode::PerFace);
    o.fadeNs = 0;
    OverlaySelection s(catalogue(), o, 0);
    s.setAutomatic(firmware::OverlayRule::Birthday, 3);
    s.setAutomatic(firmware::OverlayRule::Day, 1);
    const std::vector<vision::TrackedFace> two{face(1, 100.f), face(2, 80.f)};
    s.update(two, ms(0));
    EXPECT_EQ(s.choiceFor(1).overlay, 1) << "the day, the birthday is nobody's yet";
    EXPECT_EQ(s.ruleFor(1), firmware::OverlayRule::Day);

    s.setBirthday(2, true);
    s.setKept(1, true, 2);
    s.update(two, ms(40));
    EXPECT_EQ(s.choiceFor(1).overlay, 2) << "face 1's person's kept choice";
    EXPECT_EQ(s.ruleFor(1), firmware::OverlayRule::Person);
    EXPECT_EQ(s.choiceFor(2).overlay, 3) << "face 2's birthday, on face 2 alone";
    EXPECT_EQ(s.ruleFor(2), firmware::OverlayRule::Birthday);
    int own = -2;
    EXPECT_FALSE(s.ownChoice(1, own)) << "a kept choice is not one made on screen";

    s.select(0);  // per_face: the target face (the largest, face 1) chooses on screen
    s.update(two, ms(80));
    ASSERT_TRUE(s.ownChoice(1, own));
    EXPECT_EQ(own, 0);
    EXPECT_EQ(s.choiceFor(1).overlay, 0) << "the choice made now beats the kept one";
    s.setKept(2, true, -1);
    s.update(two, ms(120));
    EXPECT_EQ(s.choiceFor(2).overlay, -1) << "a kept none beats the birthday";
    s.setKept(2, false, -1);
    s.setBirthday(2, false);
    s.update(two, ms(160));
    EXPECT_EQ(s.ruleFor(2), firmware::OverlayRule::Day) << "taken back";
}
