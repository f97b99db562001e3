#pragma once
// PersonStore: the people the mirror knows, one file each in `[state] dir/people/` (§6: "different
// hats on different family members"). A file keeps only the numbers of the person's face
// signature (vision::FaceSignature), never an image, and what the mirror does for them: their own
// overlay and their birthday. `people/anna.toml`:
//
//   # a person the mirror knows (person add): their face signature's numbers, never an image
//   name = "anna"
//   model = "crc32:1a2b3c4d"   # the AAM model the signature was taken with
//   samples = 24               # fits averaged into it
//   shape = [...]              # FaceSignature::shapeUnits
//   appearance = [...]         # FaceSignature::appearance (appearanceCount of them)
//   overlay = "top_hat"        # optional: what they chose to wear ("none" is a choice too)
//   birthday = "03-14"         # optional: MM-DD
//
// A signature means something only for the model it was taken with: a file of another model
// (its CRC-32 differs), a corrupt or unreadable one is skipped at start with one warning naming
// it, and left on disk. Files are written atomically (temp file, fsync, rename), mode 0600, from
// the frame loop, so saving never allocates: a Person is fixed-size and the text goes into a
// fixed buffer. Names become file names: 1-32 of a-z, A-Z, 0-9, '_' and '-', starting with a
// letter or digit; "guest" is what an unknown face is called and not a name.

#include "vision/face_signature.hpp"
#include "vision/person_gallery.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace firmware {

inline constexpr std::size_t kMaxPersonNameLength = 32;
inline constexpr std::size_t kMaxPersonOverlayLength = 128;

struct Person {
    char name[kMaxPersonNameLength + 1] = "";
    vision::FaceSignature signature{};
    /// Their own overlay: "" when they chose none yet, else a catalogue name or "none".
    char overlay[kMaxPersonOverlayLength + 1] = "";
    int birthdayMonth = 0;  ///< 0: no birthday kept
    int birthdayDay = 0;
};

/// Whether `name` may be a person's name; when not, `why` says so in a few words.
bool checkPersonName(std::string_view name, const char*& why) noexcept;
/// "MM-DD" (a day that exists in some year: 02-29 is one) into month and day.
bool parseBirthday(std::string_view text, int& month, int& day) noexcept;
/// Copies `text` into `out` (capacity `size`, NUL-terminated); false when it does not fit.
bool copyName(std::string_view text, char* out, std::size_t size) noexcept;

class PersonStore {
public:
    static constexpr int kMaxPeople = vision::PersonGallery::kMaxPeople;

    /// `[state] dir`/people, made (mode 0700) if missing and `create`; `modelId` names the AAM
    /// model (PersonStore::modelIdOf). Never throws: a folder that cannot be made is lastError().
    PersonStore(const std::string& stateDir, std::uint32_t modelId, bool create = true);

    const std::string& dir() const noexcept { return dir_; }
    bool usable() const noexcept { return usable_; }
    const char* lastError() const noexcept { return error_; }

    /// Start-up: every `*.toml` of the folder, in name order, at most kMaxPeople. Each file that
    /// is unreadable, corrupt or of another model is one line in `warnings` naming it, and left.
    std::vector<Person> loadAll(std::vector<std::string>& warnings) const;
    /// Writes `person`'s file atomically, mode 0600. Never allocates.
    bool save(const Person& person) noexcept;
    /// Removes `name`'s file (none there is fine). Never allocates.
    bool remove(const char* name) noexcept;
    /// Removes every `*.toml` in the folder (also those skipped at start); how many went.
    int removeAll() noexcept;
    /// The path of `name`'s file, in a fixed buffer valid until the next call.
    const char* pathOf(const char* name) noexcept;

    /// The identity of a model file: its header's CRC-32 of the payload (0 when it is no model).
    static std::uint32_t modelIdOf(const std::string& modelPath);

private:
    std::string dir_;
    std::uint32_t modelId_ = 0;
    bool usable_ = false;
    char error_[1280] = "";
    char path_[1024] = "";
    char tempPath_[1024] = "";
};

}  // namespace firmware
