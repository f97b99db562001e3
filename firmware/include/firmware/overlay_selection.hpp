#pragma once
// OverlaySelection: which overlay (hat, glasses...) each tracked face wears, what the buttons and
// the `overlay` console command change, and the fade that keeps overlays from popping in and out.
//
// Modes (`[overlay] mode`):
//  - global: one choice for everyone; next/prev/off/select change it and every face follows.
//  - per_face: each face keeps its own choice. A face confirmed by the tracker starts with the
//    last choice made (selected()), or, when another face on screen already wears that, with the
//    next one in the catalogue nobody wears, so two people get different hats. next/prev/select
//    act on the *target face*: the largest face on screen (the one nearest the mirror: whoever
//    presses a button on its frame stands closest), ties within 10% going to the face shown
//    longest. With no face on screen they change what the next face will start with. `off`
//    turns every face off.
// In both modes the cycle of next/prev runs through "none": none, 0, 1, ..., n-1, none, so the
// two buttons alone can also take overlays off.
//
// Above the mode's choice stand the automatic rules (firmware/overlay_rules.hpp): the calendar's
// overlay for the day and the weather's, offered by setAutomatic(), decided per face in the order
// of OverlaySelectionOptions::precedence. A choice made with the buttons or the console is the
// own choice ("person") of the faces it acted on (per_face: the target face; global: every face on
// screen), which by default beats the automatic ones for the life of their tracks: pressing a
// button always changes what the person in front of the mirror wears.
// A recognised person's face (PeopleControl) also carries what that person chose on an earlier
// visit (setKept: offered by the person rule when the face chose nothing on screen) and whether
// it is their birthday (setBirthday: the birthday rule offers its overlay to such faces alone).
//
// A face gets a state when it is first shown (TrackedFace::shown(): confirmed, or missing within
// the tracker's grace) and loses it when the tracker drops it: with no pose left there is nothing
// to draw on. Its overlay fades in from alpha 0 over `fadeNs`; a change of overlay fades the old
// one out and the new one in at twice that rate (a switch takes fadeNs in all); `off` fades out
// over fadeNs.
//
// Sizes are fixed at construction (maxFaces states); update(), choiceFor() and the actions never
// allocate and never throw. Faces beyond maxFaces wear nothing.

#include "firmware/overlay_rules.hpp"
#include "vision/face_tracker.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace firmware {

enum class OverlayMode : std::uint8_t { Global, PerFace };

/// "global" / "per_face" (the config's words).
const char* toString(OverlayMode mode) noexcept;
bool parseOverlayMode(std::string_view text, OverlayMode& out) noexcept;

/// What to draw on one face: an index into the catalogue (-1: nothing) and its opacity 0..1.
struct OverlayChoice {
    int overlay = -1;
    float alpha = 0.f;
};

/// The result of an action: the overlay now chosen (-1: none) and for which face (0: everyone in
/// global mode, or the faces still to come in per_face mode).
struct OverlayChange {
    int overlay = -1;
    int faceId = 0;
};

struct OverlaySelectionOptions {
    OverlayMode mode = OverlayMode::Global;
    std::int64_t fadeNs = 250'000'000;  ///< a full fade in or out; 0 = instant
    int maxFaces = 8;                   ///< faces with their own state at most
    OverlayPrecedence precedence = kDefaultOverlayPrecedence;
};

class OverlaySelection {
public:
    /// `names` is the catalogue in its order (indices are positions in it). `initial` is the
    /// starting selected() (-1: none). Throws std::invalid_argument on duplicate or empty names,
    /// maxFaces < 1 or a negative fade.
    OverlaySelection(std::vector<std::string> names, const OverlaySelectionOptions& options,
                     int initial = -1);

    int size() const noexcept { return static_cast<int>(names_.size()); }
    /// The overlay's name; "none" for -1 or an index out of range.
    const char* name(int overlay) const noexcept;
    /// The index of `name`, or -1 when the catalogue has no such overlay.
    int find(std::string_view name) const noexcept;

    OverlayMode mode() const noexcept { return options_.mode; }
    /// Switching to global puts every face on selected().
    void setMode(OverlayMode mode) noexcept;

    OverlayChange next() noexcept;
    OverlayChange prev() noexcept;
    OverlayChange off() noexcept;
    /// `overlay` in -1..size()-1; anything else changes nothing and returns false.
    bool select(int overlay, OverlayChange* change = nullptr) noexcept;
    /// By name ("none" or "off" for none); false, changing nothing, for an unknown name.
    bool select(std::string_view name, OverlayChange* change = nullptr) noexcept;

    /// The choice made last: everyone's in global mode, the start of new faces in per_face mode.
    /// This is what is kept across restarts.
    int selected() const noexcept { return selected_; }
    /// Changes whenever selected() or mode() changed: the caller saves the state when it moves.
    std::uint32_t generation() const noexcept { return generation_; }
    /// per_face: the face id next/prev/select act on now (0: none on screen). global: 0.
    int targetFace() const noexcept;

    /// Once per frame with the tracker's faces (Tentative ones are ignored) and the frame time.
    void update(std::span<const vision::TrackedFace> faces, std::int64_t nowNs) noexcept;
    /// What to draw on face `faceId` this frame; {-1, 0} for a face without an overlay.
    OverlayChoice choiceFor(int faceId) const noexcept;
    /// The rule that chose face `faceId`'s overlay (Global for an unknown face).
    OverlayRule ruleFor(int faceId) const noexcept;

    /// What an automatic rule (Birthday, Day or Weather) offers from the next update() on: an
    /// overlay index, or -1 to offer nothing. Day and Weather offer it to every face, Birthday
    /// only to the faces marked by setBirthday(). Other rules and indices out of range are
    /// ignored.
    void setAutomatic(OverlayRule rule, int overlay) noexcept;
    int automatic(OverlayRule rule) const noexcept;

    /// A recognised person's kept choice for face `faceId` (PeopleControl): offered by the person
    /// rule when the face made no own choice on screen; `has` false takes it back. A face without
    /// a state yet (first frame) is ignored: the caller says it again every frame.
    void setKept(int faceId, bool has, int overlay) noexcept;
    /// Whether it is face `faceId`'s person's birthday (the birthday rule offers it alone).
    void setBirthday(int faceId, bool birthday) noexcept;
    /// The overlay face `faceId` chose on screen (buttons, console), if it made an own choice.
    bool ownChoice(int faceId, int& overlay) const noexcept;

private:
    struct Slot {
        int faceId = 0;  ///< 0: free
        int wanted = -1;
        int shown = -1;
        float alpha = 0.f;
        bool fast = false;  ///< switching between two overlays: fade at twice the rate
        bool seen = false;
        bool own = false;  ///< wanted was chosen for this face (the person rule)
        bool hasKept = false;  ///< a recognised person's kept choice (setKept)
        int kept = -1;
        bool birthday = false;  ///< the person's birthday today (setBirthday)
        int target = -1;   ///< what the rules decided: what the face fades to
        OverlayRule rule = OverlayRule::Global;
        float size = 0.f;
        std::int64_t sinceNs = 0;  ///< first shown
    };

    Slot* findSlot(int faceId) noexcept;
    const Slot* findSlot(int faceId) const noexcept;
    Slot* targetSlot() noexcept;
    const Slot* targetSlot() const noexcept;
    int startChoice() const noexcept;
    int step(int from, int delta) const noexcept;
    OverlayChange apply(int overlay, bool relative, int delta) noexcept;
    void setSelected(int overlay) noexcept;
    void decide(Slot& slot) const noexcept;

    std::vector<std::string> names_;
    OverlaySelectionOptions options_;
    std::vector<Slot> slots_;
    int selected_ = -1;
    std::array<int, kOverlayRules> automatic_{-1, -1, -1, -1, -1};
    std::uint32_t generation_ = 0;
    std::int64_t lastNs_ = 0;
    bool started_ = false;
};

}  // namespace firmware
