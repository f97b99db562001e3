#pragma once
// Which rule chooses a face's overlay (§6.2 of the dissertation: "different hats on different
// family members, with special hats for special days, like birthdays", a hat for the weather):
// each rule may offer an overlay for a face, and the first rule in the configured order
// (`[overlay] precedence`) that offers one wins.
//
//  - person:   the face's own choice: made for it with the buttons or the console while it was
//              on screen (per_face mode: the target face; global mode: everyone on screen then),
//              kept for the life of its track; else, for a recognised person, the choice they
//              made on an earlier visit (kept in their file, PersonStore). Choosing "none" is a
//              choice too.
//  - birthday: `[days] birthday` on a known person's birthday, on that person alone
//              (PeopleControl).
//  - day:      the calendar's overlay for today (`[days] dates`).
//  - weather:  the overlay of the current forecast's weather code (`[weather]`).
//  - global:   the overlay selected for everyone (global mode) or the one the face started with
//              (per_face mode); "none" offers nothing.
// The default order is the list above.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace firmware {

enum class OverlayRule : std::uint8_t { Person, Birthday, Day, Weather, Global };
inline constexpr int kOverlayRules = 5;

/// "person", "birthday", "day", "weather", "global".
const char* toString(OverlayRule rule) noexcept;
bool parseOverlayRule(std::string_view text, OverlayRule& out) noexcept;

using OverlayPrecedence = std::array<OverlayRule, kOverlayRules>;
inline constexpr OverlayPrecedence kDefaultOverlayPrecedence{
    OverlayRule::Person, OverlayRule::Birthday, OverlayRule::Day, OverlayRule::Weather,
    OverlayRule::Global};

/// The order from the config's words; each rule must appear exactly once. False with one line in
/// `problem` otherwise.
bool parseOverlayPrecedence(std::span<const std::string> words, OverlayPrecedence& out,
                            std::string& problem);

/// What each rule offers one face: an overlay index (-1: none), and whether it offers at all.
struct RuleOffers {
    std::array<int, kOverlayRules> overlay{-1, -1, -1, -1, -1};
    std::array<bool, kOverlayRules> offered{};
    void offer(OverlayRule rule, int o) noexcept
    {
        overlay[static_cast<std::size_t>(rule)] = o;
        offered[static_cast<std::size_t>(rule)] = true;
    }
};

struct RuleDecision {
    int overlay = -1;
    OverlayRule rule = OverlayRule::Global;
    bool decided = false;  ///< false: no rule offered anything (nothing is worn)
};

/// The first rule of `order` that offers something.
RuleDecision decideOverlay(const OverlayPrecedence& order, const RuleOffers& offers) noexcept;

}  // namespace firmware
