#include "firmware/overlay_rules.hpp"

namespace firmware {

namespace {
constexpr const char* kNames[kOverlayRules] = {"person", "birthday", "day", "weather", "global"};
}  // namespace

const char* toString(OverlayRule rule) noexcept
{
    return kNames[static_cast<int>(rule)];
}

bool parseOverlayRule(std::string_view text, OverlayRule& out) noexcept
{
    for (int i = 0; i < kOverlayRules; ++i) {
        if (text == kNames[i]) {
            out = static_cast<OverlayRule>(i);
            return true;
        }
    }
    return false;
}

bool parseOverlayPrecedence(std::span<const std::string> words, OverlayPrecedence& out,
                            std::string& problem)
{
    if (words.size() != static_cast<std::size_t>(kOverlayRules)) {
        problem = "precedence must name each of person, birthday, day, weather, global once";
        return false;
    }
    std::array<bool, kOverlayRules> seen{};
    OverlayPrecedence order{};
    for (std::size_t i = 0; i < words.size(); ++i) {
        OverlayRule r{};
        if (!parseOverlayRule(words[i], r)) {
            problem = "precedence: '" + words[i] +
                      "' is not one of person, birthday, day, weather, global";
            return false;
        }
        if (seen[static_cast<std::size_t>(r)]) {
            problem = "precedence names '" + words[i] + "' twice";
            return false;
        }
        seen[static_cast<std::size_t>(r)] = true;
        order[i] = r;
    }
    out = order;
    return true;
}

RuleDecision decideOverlay(const OverlayPrecedence& order, const RuleOffers& offers) noexcept
{
    for (const OverlayRule r : order) {
        const auto i = static_cast<std::size_t>(r);
        if (offers.offered[i])
            return {offers.overlay[i], r, true};
    }
    return {};
}

}  // namespace firmware
