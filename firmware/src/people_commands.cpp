// PeopleControl's console: `person list|add|rename|forget|birthday`, one line each.
#include "firmware/log.hpp"
#include "people_control.hpp"

#include <cstdio>
#include <cstring>

namespace firmware {

void PeopleControl::command(const Args& args, std::span<const vision::TrackedFace> faces,
                            std::span<const vision::FaceFit> fits, std::int64_t nowNs,
                            Reply& reply) noexcept
{
    const int what =
        args.size() == 1 ? 0 : args.choice(1, {"list", "add", "rename", "forget", "birthday"});
    const std::size_t words[] = {2, 3, 4, 3, 4};  // each form's words with "person"
    static constexpr const char* kForms[] = {"list", "add NAME", "rename OLD NEW",
                                             "forget NAME|--all", "birthday NAME MM-DD|none"};
    if (what < 0) {
        reply.usageError("unknown '%.*s'", Args::shown(args[1]), args[1].data());
        return;
    }
    if (args.size() != words[what] && !(what == 0 && args.size() == 1)) {
        reply.usageError("expected person %s", kForms[what]);
        return;
    }
    if (aam_ == nullptr && what != 0) {
        reply.printf("error: no AAM model ([faces] model): the mirror cannot tell faces apart\n");
        return;
    }
    switch (what) {
        case 0:
            listCommand(reply);
            break;
        case 1:
            addCommand(args, faces, fits, nowNs, reply);
            break;
        case 2:
            renameCommand(args, reply);
            break;
        case 3:
            forgetCommand(args, reply);
            break;
        default:
            birthdayCommand(args, reply);
            break;
    }
}

void PeopleControl::listCommand(Reply& reply) const noexcept
{
    if (aam_ == nullptr) {
        reply.printf("people: off (no AAM model)\n");
        return;
    }
    if (known() == 0) {
        reply.printf("people: nobody known (person add NAME)\n");
        return;
    }
    reply.printf("people: %d known:", known());
    for (const Person& p : people_) {
        if (!p.name[0])
            continue;
        reply.printf(" %s", p.name);
        if (p.overlay[0] && p.birthdayMonth > 0)
            reply.printf(" (%s, birthday %02d-%02d)", p.overlay, p.birthdayMonth, p.birthdayDay);
        else if (p.overlay[0])
            reply.printf(" (%s)", p.overlay);
        else if (p.birthdayMonth > 0)
            reply.printf(" (birthday %02d-%02d)", p.birthdayMonth, p.birthdayDay);
    }
    reply.printf("\n");
}

void PeopleControl::addCommand(const Args& args, std::span<const vision::TrackedFace> faces,
                               std::span<const vision::FaceFit> fits, std::int64_t nowNs,
                               Reply& reply) noexcept
{
    const std::string_view name = args[2];
    int shown = 0, faceId = 0;
    for (const vision::TrackedFace& f : faces)
        if (f.shown()) {
            ++shown;
            faceId = f.id;
        }
    const char* why = "";
    // The name first: a wrong name is wrong whoever stands there.
    if (!checkPersonName(name, why)) {
        reply.usageError("person add: '%.*s': %s", Args::shown(name), name.data(), why);
        return;
    }
    if (shown != 1) {
        reply.printf("error: person add: %s; enrolment needs exactly one face in view\n",
                     shown == 0 ? "no face in view" : "several faces in view");
        return;
    }
    if (!startEnrolment(name, faceId, fits, nowNs)) {
        reply.printf("error: person add: %s\n", message_);
        return;
    }
    reply.printf("person add %.*s: collecting %d fits of face %d: hold still, face the mirror\n",
                 Args::shown(name), name.data(), enrolFits_, faceId);
}

void PeopleControl::renameCommand(const Args& args, Reply& reply) noexcept
{
    const std::string_view from = args[2], to = args[3];
    const int id = find(from);
    const char* why = "";
    if (id == 0) {
        reply.printf("error: person rename: nobody called '%.*s'\n", Args::shown(from),
                     from.data());
        return;
    }
    if (!checkPersonName(to, why)) {
        reply.usageError("person rename: '%.*s': %s", Args::shown(to), to.data(), why);
        return;
    }
    if (find(to) != 0 || (enrolment_.active && to == enrolment_.name)) {
        reply.printf("error: person rename: '%.*s' is taken\n", Args::shown(to), to.data());
        return;
    }
    Person& p = people_[static_cast<std::size_t>(id - 1)];
    char old[sizeof p.name];
    std::memcpy(old, p.name, sizeof old);
    copyName(to, p.name, sizeof p.name);
    // The new file first: a failure leaves the old one, and the person as they were.
    if (!store_.save(p)) {
        reply.printf("error: person rename: %s\n", store_.lastError());
        std::memcpy(p.name, old, sizeof old);
        return;
    }
    if (!store_.remove(old))
        MIRROR_LOG_WARN("people: %s", store_.lastError());
    MIRROR_LOG_INFO("people: %s is now %s", old, p.name);
    reply.printf("person: %s is now %s\n", old, p.name);
}

void PeopleControl::forgetCommand(const Args& args, Reply& reply) noexcept
{
    const std::string_view name = args[2];
    if (name == "--all") {
        const int files = store_.removeAll();
        for (std::size_t i = 0; i < people_.size(); ++i)
            if (people_[i].name[0])
                forgetId(static_cast<int>(i) + 1);
        gallery_.clear();
        MIRROR_LOG_INFO("people: forgot everyone (%d files)", files);
        reply.printf("person: forgot everyone (%d files removed)\n", files);
        return;
    }
    const int id = find(name);
    if (id == 0) {
        reply.printf("error: person forget: nobody called '%.*s'\n", Args::shown(name),
                     name.data());
        return;
    }
    if (!store_.remove(people_[static_cast<std::size_t>(id - 1)].name)) {
        reply.printf("error: person forget: %s\n", store_.lastError());
        return;
    }
    forgetId(id);
    MIRROR_LOG_INFO("people: forgot %.*s", Args::shown(name), name.data());
    reply.printf("person: forgot %.*s\n", Args::shown(name), name.data());
}

void PeopleControl::birthdayCommand(const Args& args, Reply& reply) noexcept
{
    const int id = find(args[2]);
    if (id == 0) {
        reply.printf("error: person birthday: nobody called '%.*s'\n", Args::shown(args[2]),
                     args[2].data());
        return;
    }
    Person& p = people_[static_cast<std::size_t>(id - 1)];
    int month = 0, day = 0;
    if (args[3] != "none" && !parseBirthday(args[3], month, day)) {
        reply.usageError("'%.*s' is not MM-DD (or none)", Args::shown(args[3]), args[3].data());
        return;
    }
    const int oldMonth = p.birthdayMonth, oldDay = p.birthdayDay;
    p.birthdayMonth = month;
    p.birthdayDay = day;
    if (!store_.save(p)) {
        p.birthdayMonth = oldMonth;
        p.birthdayDay = oldDay;
        reply.printf("error: person birthday: %s\n", store_.lastError());
        return;
    }
    if (month == 0)
        reply.printf("person: %s has no birthday kept\n", p.name);
    else
        reply.printf("person: %s's birthday is %02d-%02d\n", p.name, month, day);
}

}  // namespace firmware
