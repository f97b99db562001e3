#include "people_control.hpp"

#include "firmware/log.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace firmware {

PeopleControl::PeopleControl(const Config& config, vision::AamStage* aam, std::uint32_t modelId,
                             OverlaySelection* selection)
    : aam_(aam),
      selection_(selection),
      // Without a model nobody is enrolled: no folder made for them.
      store_(config.state.dir, modelId, aam != nullptr),
      enrolFits_(config.people.enrolFits),
      enrolTimeoutNs_(static_cast<std::int64_t>(config.people.enrolTimeoutS) * 1'000'000'000)
{
    if (aam_ != nullptr && !store_.usable())
        MIRROR_LOG_WARN("people: %s; nobody is kept", store_.lastError());
    if (selection_) {
        const std::string& birthday = config.days.birthday;
        const int index = selection_->find(birthday);
        if (index < 0 && birthday != "none")
            MIRROR_LOG_WARN("days.birthday: the catalogue has no overlay '%s'; none for it",
                            birthday.c_str());
        selection_->setAutomatic(OverlayRule::Birthday, index);
    }
    if (aam_ == nullptr) {
        MIRROR_LOG_INFO("people: no AAM model ([faces] model): faces are not told apart");
        return;
    }
    std::vector<std::string> warnings;
    const std::vector<Person> people = store_.loadAll(warnings);
    for (const std::string& w : warnings)
        MIRROR_LOG_WARN("%s", w.c_str());
    for (std::size_t i = 0; i < people.size(); ++i) {
        people_[i] = people[i];
        gallery_.enrol(static_cast<int>(i) + 1, people[i].signature);
    }
    MIRROR_LOG_INFO("people: %d known from %s", known(), store_.dir().c_str());
}

int PeopleControl::known() const noexcept
{
    return static_cast<int>(
        std::count_if(people_.begin(), people_.end(), [](const Person& p) { return p.name[0]; }));
}

int PeopleControl::find(std::string_view name) const noexcept
{
    for (std::size_t i = 0; i < people_.size(); ++i)
        if (people_[i].name[0] && name == people_[i].name)
            return static_cast<int>(i) + 1;
    return 0;
}

int PeopleControl::freeId() const noexcept
{
    for (std::size_t i = 0; i < people_.size(); ++i)
        if (!people_[i].name[0])
            return static_cast<int>(i) + 1;
    return 0;
}

PeopleControl::Track* PeopleControl::trackFor(int faceId) noexcept
{
    for (Track& t : tracks_)
        if (t.faceId == faceId)
            return &t;
    return nullptr;
}

const PeopleControl::Track* PeopleControl::trackFor(int faceId) const noexcept
{
    return const_cast<PeopleControl*>(this)->trackFor(faceId);
}

const char* PeopleControl::nameOf(int faceId) const noexcept
{
    const Track* t = faceId != 0 ? trackFor(faceId) : nullptr;
    if (!t || !t->decided)
        return nullptr;
    return t->match.personId > 0 ? people_[static_cast<std::size_t>(t->match.personId - 1)].name
                                 : "guest";
}

const char* PeopleControl::say(const char* format, ...) noexcept
{
    va_list args;
    va_start(args, format);
    std::vsnprintf(message_, sizeof message_, format, args);
    va_end(args);
    return message_;
}

bool PeopleControl::save(int id) noexcept
{
    const Person& p = people_[static_cast<std::size_t>(id - 1)];
    if (store_.save(p))
        return true;
    MIRROR_LOG_WARN("people: %s not kept: %s", p.name, store_.lastError());
    return false;
}

void PeopleControl::forgetId(int id) noexcept
{
    gallery_.forget(id);
    people_[static_cast<std::size_t>(id - 1)] = Person{};
    // The faces that were them are nobody now, and wear nothing of theirs.
    for (Track& t : tracks_) {
        if (t.faceId == 0 || (t.match.personId != id && t.match.nearestId != id))
            continue;
        t.match = vision::PersonMatch{};
        if (selection_) {
            selection_->setKept(t.faceId, false, -1);
            selection_->setBirthday(t.faceId, false);
        }
    }
}

bool PeopleControl::startEnrolment(std::string_view name, int faceId,
                                   std::span<const vision::FaceFit> fits,
                                   std::int64_t nowNs) noexcept
{
    const char* why = "";
    if (aam_ == nullptr) {
        say("no AAM model ([faces] model): the mirror cannot tell faces apart");
        return false;
    }
    if (enrolment_.active) {
        say("still enrolling %s; wait for it to finish", enrolment_.name);
        return false;
    }
    if (!checkPersonName(name, why)) {
        say("'%.*s': %s", Args::shown(name), name.data(), why);
        return false;
    }
    if (find(name) != 0) {
        say("'%.*s' is taken (person rename or person forget first)", Args::shown(name),
            name.data());
        return false;
    }
    if (freeId() == 0) {
        say("the mirror knows %d people already, the most it keeps", PersonStore::kMaxPeople);
        return false;
    }
    if (!store_.usable()) {
        say("nowhere to keep them: %s", store_.lastError());
        return false;
    }
    const vision::FaceFit* fit = vision::fitFor(fits, faceId);
    if (fit == nullptr || !aam_->fitter().collectSignature(faceId, enrolFits_)) {
        say("face %d is not fitted yet; try again in a moment", faceId);
        return false;
    }
    enrolment_ = Enrolment{};
    enrolment_.active = true;
    enrolment_.faceId = faceId;
    copyName(name, enrolment_.name, sizeof enrolment_.name);
    enrolment_.startSamples = fit->signature.samples;
    enrolment_.deadlineNs = nowNs + enrolTimeoutNs_;
    // The face is being enrolled: it is matched against nobody meanwhile.
    if (Track* t = trackFor(faceId))
        t->decided = false;
    return true;
}

const char* PeopleControl::advanceEnrolment(std::span<const vision::TrackedFace> faces,
                                            std::span<const vision::FaceFit> fits,
                                            std::int64_t nowNs) noexcept
{
    Enrolment& e = enrolment_;
    const bool present = std::any_of(faces.begin(), faces.end(), [&](const vision::TrackedFace& f) {
        return f.id == e.faceId && f.shown();
    });
    const vision::FaceFit* fit = vision::fitFor(fits, e.faceId);
    const int have = fit ? fit->signature.samples - e.startSamples : 0;
    if (!present || fit == nullptr) {
        e.active = false;
        return say("person add %s: failed: the face left after %d of %d fits", e.name,
                   std::max(have, 0), enrolFits_);
    }
    if (fit->signatureSettled && have >= enrolFits_) {
        e.active = false;
        const int id = freeId();
        if (id == 0 || find(e.name) != 0)
            return say("person add %s: failed: the name was taken meanwhile", e.name);
        Person& p = people_[static_cast<std::size_t>(id - 1)];
        p = Person{};
        copyName(e.name, p.name, sizeof p.name);
        p.signature = fit->signature;
        if (!store_.save(p)) {
            const char* error = store_.lastError();
            p = Person{};
            return say("person add %s: failed: not kept: %s", e.name, error);
        }
        gallery_.enrol(id, p.signature);
        if (Track* t = trackFor(e.faceId)) {
            t->decided = true;
            t->match = vision::PersonMatch{id, 1.f, id, 1.f};
        }
        MIRROR_LOG_INFO("people: enrolled %s from %d fits (face %d)", p.name, p.signature.samples,
                        e.faceId);
        return say("enrolled %s from %d fits", p.name, p.signature.samples);
    }
    if (nowNs > e.deadlineNs) {
        e.active = false;
        return say(
            "person add %s: failed: only %d of %d fits held in time (face the mirror, hold "
            "still)",
            e.name, std::max(have, 0), enrolFits_);
    }
    return nullptr;
}

void PeopleControl::recognise(std::span<const vision::TrackedFace> faces,
                              std::span<const vision::FaceFit> fits) noexcept
{
    for (Track& t : tracks_)
        t.seen = false;
    for (const vision::TrackedFace& f : faces) {
        if (!f.shown() || f.id == 0)
            continue;
        Track* t = trackFor(f.id);
        if (!t && (t = trackFor(0)) != nullptr) {
            *t = Track{};
            t->faceId = f.id;
        }
        if (!t)
            continue;  // more faces than the table: this one stays undecided
        t->seen = true;
        if (t->decided || (enrolment_.active && enrolment_.faceId == f.id))
            continue;
        // Once per track: the settled signature no longer changes.
        const vision::FaceFit* fit = vision::fitFor(fits, f.id);
        if (fit && fit->signatureSettled) {
            t->match = gallery_.match(fit->signature);
            t->decided = true;
            if (t->match.personId > 0)
                MIRROR_LOG_INFO("people: face %d is %s (score %.2f)", f.id,
                                people_[static_cast<std::size_t>(t->match.personId - 1)].name,
                                static_cast<double>(t->match.score));
        }
    }
    for (Track& t : tracks_)
        if (t.faceId != 0 && !t.seen)
            t = Track{};
}

void PeopleControl::keepOwnChoice(Track& t) noexcept
{
    // per_face mode: what a known person chose on screen is theirs, kept for their next visit.
    int overlay = -1;
    if (selection_->mode() != OverlayMode::PerFace || !selection_->ownChoice(t.faceId, overlay))
        return;
    Person& p = people_[static_cast<std::size_t>(t.match.personId - 1)];
    const char* name = selection_->name(overlay);
    if (std::strcmp(p.overlay, name) == 0 || !copyName(name, p.overlay, sizeof p.overlay))
        return;
    if (save(t.match.personId))
        MIRROR_LOG_INFO("people: %s wears %s from now on", p.name, name);
}

void PeopleControl::applyToSelection() noexcept
{
    for (Track& t : tracks_) {
        if (t.faceId == 0)
            continue;
        if (!t.decided || t.match.personId <= 0) {
            selection_->setKept(t.faceId, false, -1);
            selection_->setBirthday(t.faceId, false);
            continue;
        }
        keepOwnChoice(t);
        const Person& p = people_[static_cast<std::size_t>(t.match.personId - 1)];
        const bool none = std::strcmp(p.overlay, "none") == 0;
        const int overlay = none ? -1 : selection_->find(p.overlay);
        // A kept name the catalogue no longer has is no choice.
        selection_->setKept(t.faceId, p.overlay[0] != '\0' && (none || overlay >= 0), overlay);
        selection_->setBirthday(
            t.faceId, p.birthdayMonth > 0 && isYearlyDate(p.birthdayMonth, p.birthdayDay, today_));
    }
}

const char* PeopleControl::update(std::span<const vision::TrackedFace> faces,
                                  std::span<const vision::FaceFit> fits,
                                  std::int64_t nowNs) noexcept
{
    if (aam_ == nullptr)
        return nullptr;
    if (const std::time_t now = std::time(nullptr); now != todayAt_) {
        todayAt_ = now;
        today_ = localDay(now);
    }
    const char* message = enrolment_.active ? advanceEnrolment(faces, fits, nowNs) : nullptr;
    recognise(faces, fits);
    if (selection_)
        applyToSelection();
    return message;
}

const char* PeopleControl::enrolGuest(std::span<const vision::TrackedFace> faces,
                                      std::span<const vision::FaceFit> fits,
                                      std::int64_t nowNs) noexcept
{
    const vision::TrackedFace* nearest = nullptr;
    for (const vision::TrackedFace& f : faces)
        if (f.shown() && (!nearest || f.size > nearest->size))
            nearest = &f;
    if (!nearest)
        return say("guest button: no face in view");
    char name[kMaxPersonNameLength + 1];
    for (int n = 1; n <= PersonStore::kMaxPeople + 1; ++n) {
        std::snprintf(name, sizeof name, "guest-%d", n);
        if (find(name) == 0 && !(enrolment_.active && std::strcmp(enrolment_.name, name) == 0))
            break;
    }
    if (!startEnrolment(name, nearest->id, fits, nowNs)) {
        char why[sizeof message_];
        std::memcpy(why, message_, sizeof why);
        return say("guest button: %s", why);
    }
    return say("guest button: enrolling face %d as %s: hold still", nearest->id, name);
}

void PeopleControl::formatFace(int faceId, Reply& reply) const noexcept
{
    const Track* t = trackFor(faceId);
    if (enrolment_.active && enrolment_.faceId == faceId) {
        reply.printf("face %d: person=? (enrolling as %s)\n", faceId, enrolment_.name);
    } else if (!t || !t->decided) {
        reply.printf("face %d: person=? (signature not settled)\n", faceId);
    } else if (t->match.personId > 0) {
        reply.printf("face %d: person=%s score=%.2f\n", faceId,
                     people_[static_cast<std::size_t>(t->match.personId - 1)].name,
                     static_cast<double>(t->match.score));
    } else if (t->match.nearestId > 0) {
        reply.printf("face %d: person=guest nearest=%s %.2f\n", faceId,
                     people_[static_cast<std::size_t>(t->match.nearestId - 1)].name,
                     static_cast<double>(t->match.nearestScore));
    } else {
        reply.printf("face %d: person=guest\n", faceId);
    }
}

void PeopleControl::formatFaces(std::span<const vision::TrackedFace> faces,
                                Reply& reply) const noexcept
{
    if (aam_ == nullptr)
        return;
    for (const vision::TrackedFace& f : faces)
        if (f.shown())
            formatFace(f.id, reply);
}

void PeopleControl::formatStatus(std::span<const vision::TrackedFace> faces,
                                 Reply& reply) const noexcept
{
    if (aam_ == nullptr) {
        reply.printf("people: off (no AAM model)\n");
        return;
    }
    reply.printf("people: %d known%s%s\n", known(), enrolment_.active ? ", enrolling " : "",
                 enrolment_.active ? enrolment_.name : "");
    formatFaces(faces, reply);
}

void PeopleControl::formatJson(std::span<const vision::TrackedFace> faces,
                               Reply& reply) const noexcept
{
    reply.printf(",\"people\":{\"known\":%d,\"faces\":[", known());
    bool first = true;
    for (const vision::TrackedFace& f : faces) {
        if (!f.shown())
            continue;
        // Names are of a safe charset (checkPersonName): nothing to escape.
        const char* name = aam_ ? nameOf(f.id) : nullptr;
        const Track* t = trackFor(f.id);
        reply.printf("%s{\"id\":%d,\"person\":%s%s%s,\"score\":%.2f}", first ? "" : ",", f.id,
                     name ? "\"" : "", name ? name : "null", name ? "\"" : "",
                     t && name ? static_cast<double>(t->match.score) : 0.0);
        first = false;
    }
    reply.append("]}");
}

}  // namespace firmware
