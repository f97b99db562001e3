#include "firmware/overlay_selection.hpp"

#include <algorithm>
#include <stdexcept>

namespace firmware {

const char* toString(OverlayMode mode) noexcept
{
    return mode == OverlayMode::PerFace ? "per_face" : "global";
}

bool parseOverlayMode(std::string_view text, OverlayMode& out) noexcept
{
    if (text == "global") {
        out = OverlayMode::Global;
        return true;
    }
    if (text == "per_face") {
        out = OverlayMode::PerFace;
        return true;
    }
    return false;
}

OverlaySelection::OverlaySelection(std::vector<std::string> names,
                                   const OverlaySelectionOptions& options, int initial)
    : names_(std::move(names)), options_(options)
{
    if (options.maxFaces < 1)
        throw std::invalid_argument("overlay selection: maxFaces must be at least 1");
    if (options.fadeNs < 0)
        throw std::invalid_argument("overlay selection: the fade time cannot be negative");
    for (std::size_t i = 0; i < names_.size(); ++i) {
        if (names_[i].empty() || names_[i] == "none" || names_[i] == "off")
            throw std::invalid_argument("overlay selection: overlay " + std::to_string(i) +
                                        " has no usable name ('" + names_[i] + "')");
        for (std::size_t j = 0; j < i; ++j) {
            if (names_[i] == names_[j])
                throw std::invalid_argument("overlay selection: two overlays are called '" +
                                            names_[i] + "'");
        }
    }
    slots_.resize(static_cast<std::size_t>(options.maxFaces));
    if (initial >= 0 && initial < size())
        selected_ = initial;
}

const char* OverlaySelection::name(int overlay) const noexcept
{
    if (overlay < 0 || overlay >= size())
        return "none";
    return names_[static_cast<std::size_t>(overlay)].c_str();
}

int OverlaySelection::find(std::string_view name) const noexcept
{
    for (int i = 0; i < size(); ++i) {
        if (names_[static_cast<std::size_t>(i)] == name)
            return i;
    }
    return -1;
}

void OverlaySelection::setSelected(int overlay) noexcept
{
    if (overlay != selected_) {
        selected_ = overlay;
        ++generation_;
    }
}

void OverlaySelection::setMode(OverlayMode mode) noexcept
{
    if (mode == options_.mode)
        return;
    options_.mode = mode;
    ++generation_;
    if (mode == OverlayMode::Global) {
        for (Slot& s : slots_)
            s.wanted = selected_;
    }
}

int OverlaySelection::step(int from, int delta) const noexcept
{
    // Positions 0..n stand for none, 0, ..., n-1.
    const int positions = size() + 1;
    const int position = ((from + 1 + delta) % positions + positions) % positions;
    return position - 1;
}

OverlaySelection::Slot* OverlaySelection::findSlot(int faceId) noexcept
{
    // faceId 0 finds a free state.
    for (Slot& s : slots_) {
        if (s.faceId == faceId)
            return &s;
    }
    return nullptr;
}

const OverlaySelection::Slot* OverlaySelection::findSlot(int faceId) const noexcept
{
    return const_cast<OverlaySelection*>(this)->findSlot(faceId);
}

OverlaySelection::Slot* OverlaySelection::targetSlot() noexcept
{
    float largest = 0.f;
    for (const Slot& s : slots_) {
        if (s.faceId != 0)
            largest = std::max(largest, s.size);
    }
    Slot* best = nullptr;
    for (Slot& s : slots_) {
        if (s.faceId == 0 || s.size < 0.9f * largest)
            continue;
        if (!best || s.sinceNs < best->sinceNs ||
            (s.sinceNs == best->sinceNs && s.faceId < best->faceId))
            best = &s;
    }
    return best;
}

const OverlaySelection::Slot* OverlaySelection::targetSlot() const noexcept
{
    return const_cast<OverlaySelection*>(this)->targetSlot();
}

int OverlaySelection::targetFace() const noexcept
{
    if (options_.mode != OverlayMode::PerFace)
        return 0;
    const Slot* s = targetSlot();
    return s ? s->faceId : 0;
}

OverlayChange OverlaySelection::apply(int overlay, bool relative, int delta) noexcept
{
    if (options_.mode == OverlayMode::PerFace) {
        if (Slot* target = targetSlot()) {
            target->wanted = relative ? step(target->target, delta) : overlay;
            target->own = true;
            setSelected(target->wanted);
            return {target->wanted, target->faceId};
        }
    }
    setSelected(relative ? step(selected_, delta) : overlay);
    if (options_.mode == OverlayMode::Global) {
        for (Slot& s : slots_) {
            s.wanted = selected_;
            s.own = s.faceId != 0;  // everyone on screen now chose it
        }
    }
    return {selected_, 0};
}

OverlayChange OverlaySelection::next() noexcept
{
    return apply(0, true, +1);
}

OverlayChange OverlaySelection::prev() noexcept
{
    return apply(0, true, -1);
}

OverlayChange OverlaySelection::off() noexcept
{
    setSelected(-1);
    for (Slot& s : slots_) {
        s.wanted = -1;
        s.own = s.faceId != 0;
    }
    return {-1, 0};
}

bool OverlaySelection::select(int overlay, OverlayChange* change) noexcept
{
    if (overlay < -1 || overlay >= size())
        return false;
    const OverlayChange result = apply(overlay, false, 0);
    if (change)
        *change = result;
    return true;
}

bool OverlaySelection::select(std::string_view name, OverlayChange* change) noexcept
{
    const int overlay = (name == "none" || name == "off") ? -1 : find(name);
    if (overlay < 0 && name != "none" && name != "off")
        return false;
    return select(overlay, change);
}

int OverlaySelection::startChoice() const noexcept
{
    if (options_.mode == OverlayMode::Global || selected_ < 0)
        return selected_;
    // per_face: the last choice, unless someone on screen wears it already.
    for (int k = 0; k < size(); ++k) {
        const int candidate = (selected_ + k) % size();
        const bool worn = std::any_of(slots_.begin(), slots_.end(), [&](const Slot& s) {
            return s.faceId != 0 && s.wanted == candidate;
        });
        if (!worn)
            return candidate;
    }
    return selected_;
}

void OverlaySelection::update(std::span<const vision::TrackedFace> faces,
                              std::int64_t nowNs) noexcept
{
    const std::int64_t dt = started_ ? std::max<std::int64_t>(0, nowNs - lastNs_) : 0;
    started_ = true;
    lastNs_ = std::max(lastNs_, nowNs);

    // Known faces first, then forget the dropped ones, so their states are free for new faces.
    for (Slot& s : slots_)
        s.seen = false;
    for (const vision::TrackedFace& face : faces) {
        if (!face.shown() || face.id == 0)
            continue;
        if (Slot* slot = findSlot(face.id)) {
            slot->seen = true;
            slot->size = face.size;
        }
    }
    for (Slot& s : slots_) {
        if (s.faceId != 0 && !s.seen)
            s = Slot{};
    }
    for (const vision::TrackedFace& face : faces) {
        if (!face.shown() || face.id == 0 || findSlot(face.id))
            continue;
        Slot* slot = findSlot(0);
        if (!slot)
            continue;  // more faces than states: this one wears nothing
        const int start = startChoice();
        *slot = Slot{};
        slot->faceId = face.id;
        slot->wanted = slot->shown = start;
        decide(*slot);
        slot->shown = slot->target;
        slot->sinceNs = nowNs;
        slot->seen = true;
        slot->size = face.size;
    }

    const double fadeNs = static_cast<double>(options_.fadeNs);
    for (Slot& s : slots_) {
        if (s.faceId == 0)
            continue;
        if (options_.mode == OverlayMode::Global)
            s.wanted = selected_;
        decide(s);
        if (options_.fadeNs == 0) {
            s.shown = s.target;
            s.alpha = s.shown >= 0 ? 1.f : 0.f;
            continue;
        }
        if (s.sinceNs == nowNs && s.alpha == 0.f && s.shown == s.target)
            continue;  // first frame of a new face: it starts invisible
        if (s.shown != s.target) {
            if (s.shown < 0 || s.alpha <= 0.f) {
                s.shown = s.target;  // nothing visible to fade out: start the new one
                s.alpha = 0.f;
            } else {
                s.fast = s.target >= 0;
                const float rate = static_cast<float>(dt / fadeNs) * (s.fast ? 2.f : 1.f);
                s.alpha = std::max(0.f, s.alpha - rate);
                if (s.alpha == 0.f)
                    s.shown = s.target;
                continue;
            }
        }
        if (s.shown < 0) {
            s.alpha = 0.f;
            s.fast = false;
            continue;
        }
        const float rate = static_cast<float>(dt / fadeNs) * (s.fast ? 2.f : 1.f);
        s.alpha = std::min(1.f, s.alpha + rate);
        if (s.alpha == 1.f)
            s.fast = false;
    }
}

void OverlaySelection::decide(Slot& s) const noexcept
{
    RuleOffers offers;
    if (s.own)
        offers.offer(OverlayRule::Person, s.wanted);
    else if (s.hasKept)  // the person's choice of an earlier visit
        offers.offer(OverlayRule::Person, s.kept);
    for (const OverlayRule r : {OverlayRule::Birthday, OverlayRule::Day, OverlayRule::Weather}) {
        if (r == OverlayRule::Birthday && !s.birthday)
            continue;
        if (const int o = automatic_[static_cast<std::size_t>(r)]; o >= 0)
            offers.offer(r, o);
    }
    if (s.wanted >= 0)  // global: selected_; per_face: what the face started with
        offers.offer(OverlayRule::Global, s.wanted);
    const RuleDecision d = decideOverlay(options_.precedence, offers);
    s.target = d.decided ? d.overlay : -1;
    s.rule = d.decided ? d.rule : OverlayRule::Global;
}

void OverlaySelection::setAutomatic(OverlayRule rule, int overlay) noexcept
{
    if (rule == OverlayRule::Person || rule == OverlayRule::Global || overlay < -1 ||
        overlay >= size())
        return;
    automatic_[static_cast<std::size_t>(rule)] = overlay;
}

int OverlaySelection::automatic(OverlayRule rule) const noexcept
{
    return automatic_[static_cast<std::size_t>(rule)];
}

void OverlaySelection::setKept(int faceId, bool has, int overlay) noexcept
{
    if (faceId == 0 || overlay < -1 || overlay >= size())
        return;
    if (Slot* s = findSlot(faceId)) {
        s->hasKept = has;
        s->kept = has ? overlay : -1;
    }
}

void OverlaySelection::setBirthday(int faceId, bool birthday) noexcept
{
    if (faceId == 0)
        return;
    if (Slot* s = findSlot(faceId))
        s->birthday = birthday;
}

bool OverlaySelection::ownChoice(int faceId, int& overlay) const noexcept
{
    const Slot* s = faceId != 0 ? findSlot(faceId) : nullptr;
    if (!s || !s->own)
        return false;
    overlay = s->wanted;
    return true;
}

OverlayRule OverlaySelection::ruleFor(int faceId) const noexcept
{
    const Slot* s = findSlot(faceId);
    return s ? s->rule : OverlayRule::Global;
}

OverlayChoice OverlaySelection::choiceFor(int faceId) const noexcept
{
    const Slot* s = findSlot(faceId);
    if (!s || s->shown < 0)
        return {};
    return {s->shown, s->alpha};
}

}  // namespace firmware
