#pragma once
// PeopleControl: the mirror knows people (§6; dissertation 6.2: "different hats on different
// family members"). Holds the people of the state folder (PersonStore) in a PersonGallery, and
//  - per track, once its FaceFit::signature settled, matches it against the gallery once and keeps
//    who it is for the track's life (a fixed table: no allocation); unknown is a guest;
//  - enrols a face as a named person (`person add NAME`, the guest button): a state advanced each
//    frame while TrackedFaceFitter::collectSignature averages more fits, never blocking the loop;
//  - gives a recognised person their kept overlay (the person rule) and their birthday (the
//    birthday rule, on them alone), and keeps in their file what they choose on screen in
//    per_face mode;
//  - answers `person ...`, and the person lines of `faces` and `status`.
// Nothing here depends on what the signature holds (shape units, appearance): the gallery scores.

#include "firmware/command_shell.hpp"
#include "firmware/config.hpp"
#include "firmware/day_calendar.hpp"
#include "firmware/overlay_selection.hpp"
#include "firmware/person_store.hpp"
#include "vision/aam_stage.hpp"
#include "vision/person_gallery.hpp"

#include <array>
#include <cstdint>
#include <ctime>
#include <span>

namespace firmware {

class PeopleControl {
public:
    static constexpr int kMaxTracks = vision::TrackedFaceFitter::kMaxFaces;

    /// Reads the people of `[state] dir`/people/ taken with model `modelId` (each file skipped is
    /// one warning). `aam` null: no model, nobody can be told apart (every command says so).
    /// `selection` (may be null) gets the kept overlays and birthdays; it must outlive this.
    PeopleControl(const Config& config, vision::AamStage* aam, std::uint32_t modelId,
                  OverlaySelection* selection);

    /// After the vision stages of a good frame, before the overlays decide. Returns a line for
    /// the consoles when an enrolment ended (enrolled or failed), else null.
    const char* update(std::span<const vision::TrackedFace> faces,
                       std::span<const vision::FaceFit> fits, std::int64_t nowNs) noexcept;
    /// `person [list|add NAME|rename OLD NEW|forget NAME|--all|birthday NAME MM-DD|none]`.
    void command(const Args& args, std::span<const vision::TrackedFace> faces,
                 std::span<const vision::FaceFit> fits, std::int64_t nowNs, Reply& reply) noexcept;
    /// The guest button: the nearest (largest) face enrolled as the next "guest-N". Returns what
    /// happened, one line.
    const char* enrolGuest(std::span<const vision::TrackedFace> faces,
                           std::span<const vision::FaceFit> fits, std::int64_t nowNs) noexcept;
    /// One `face N: person=...` line per shown face (for `faces` and `status`).
    void formatFaces(std::span<const vision::TrackedFace> faces, Reply& reply) const noexcept;
    /// `people: N known` and the face lines.
    void formatStatus(std::span<const vision::TrackedFace> faces, Reply& reply) const noexcept;
    /// For `status --json`: `,"people":{"known":N,"faces":[{"id":1,"person":"anna","score":0.91}]}`
    /// ("person" null while undecided, "guest" for nobody known).
    void formatJson(std::span<const vision::TrackedFace> faces, Reply& reply) const noexcept;

    int known() const noexcept;
    /// Who face `faceId` is: a name, "guest", or null while it is not decided yet.
    const char* nameOf(int faceId) const noexcept;
    bool enrolling() const noexcept { return enrolment_.active; }

private:
    struct Track {
        int faceId = 0;  ///< 0: free
        bool decided = false;
        vision::PersonMatch match{};
        bool seen = false;
    };
    struct Enrolment {
        bool active = false;
        int faceId = 0;
        char name[kMaxPersonNameLength + 1] = "";
        int startSamples = 0;
        std::int64_t deadlineNs = 0;
    };

    /// Starts enrolling face `faceId` as `name`; false with the reason in message_.
    bool startEnrolment(std::string_view name, int faceId, std::span<const vision::FaceFit> fits,
                        std::int64_t nowNs) noexcept;
    const char* advanceEnrolment(std::span<const vision::TrackedFace> faces,
                                 std::span<const vision::FaceFit> fits,
                                 std::int64_t nowNs) noexcept;
    void recognise(std::span<const vision::TrackedFace> faces,
                   std::span<const vision::FaceFit> fits) noexcept;
    void applyToSelection() noexcept;
    void keepOwnChoice(Track& track) noexcept;
    Track* trackFor(int faceId) noexcept;
    const Track* trackFor(int faceId) const noexcept;
    int find(std::string_view name) const noexcept;  ///< person id (1-based), or 0
    int freeId() const noexcept;
    void forgetId(int id) noexcept;
    bool save(int id) noexcept;
    void formatFace(int faceId, Reply& reply) const noexcept;
    /// Writes one line into message_ (printf-style) and returns it.
    const char* say(const char* format, ...) noexcept __attribute__((format(printf, 2, 3)));

    void listCommand(Reply& reply) const noexcept;
    void addCommand(const Args& args, std::span<const vision::TrackedFace> faces,
                    std::span<const vision::FaceFit> fits, std::int64_t nowNs,
                    Reply& reply) noexcept;
    void renameCommand(const Args& args, Reply& reply) noexcept;
    void forgetCommand(const Args& args, Reply& reply) noexcept;
    void birthdayCommand(const Args& args, Reply& reply) noexcept;

    vision::AamStage* aam_;
    OverlaySelection* selection_;
    PersonStore store_;
    vision::PersonGallery gallery_;
    std::array<Person, PersonStore::kMaxPeople> people_{};  ///< id i+1; name "" = free
    std::array<Track, kMaxTracks> tracks_{};
    Enrolment enrolment_;
    int enrolFits_ = 24;
    std::int64_t enrolTimeoutNs_ = 15'000'000'000;
    std::time_t todayAt_ = 0;
    CalendarDay today_{};
    char message_[320] = "";
};

}  // namespace firmware
