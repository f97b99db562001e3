#pragma once
// PersonGallery: the people the mirror knows, as FaceSignatures, and which of them a face is
// (§6; dissertation 6.2: recognition from the fitted model's parameters). Fixed capacity, no
// allocation after construction: match() runs in the frame loop. The firmware owns the names and
// files; here a person is only a positive id and a signature. Why the distance is what it is:
// person_gallery.cpp.

#include "vision/face_signature.hpp"

#include <array>

namespace vision {

/// How much one person's signature varies between photographs of them, per value (its std):
/// the distance is measured in these units (whitened). Measured on the demo model's training
/// persons (person_gallery.cpp); a value beyond the table counts in its mode's own std (1).
std::array<float, kFaceSignatureMaxAppearance> defaultAppearanceSpread() noexcept;
std::array<float, kAamShapeUnits> defaultShapeSpread() noexcept;

struct PersonGalleryOptions {
    /// A face whose best score is below this is nobody enrolled (a guest).
    float acceptScore = 0.33f;
    /// What the distance weighs (0 turns a part off): the shape units, the appearance and the
    /// texture, chosen on a development model (person_gallery.cpp).
    float shapeWeight = 0.5f;
    float appearanceWeight = 1.f;
    /// The texture descriptor's weight (0: off) and its within-person spread: the rms, over the
    /// descriptor's values, of their deviation from the person's mean (in the descriptor's units,
    /// 255 = a whole cell's share; person_gallery.cpp).
    float textureWeight = 10.f;
    float textureSpread = 7.f;
    std::array<float, kFaceSignatureMaxAppearance> appearanceSpread = defaultAppearanceSpread();
    std::array<float, kAamShapeUnits> shapeSpread = defaultShapeSpread();
};

/// The best match of a signature: the person (0: a guest) and how sure, 0..1 (1: identical).
struct PersonMatch {
    int personId = 0;
    float score = 0.f;
    /// The best enrolled person's score even when it is too low to accept (for `faces`), and who.
    int nearestId = 0;
    float nearestScore = 0.f;
};

class PersonGallery {
public:
    static constexpr int kMaxPeople = 64;

    explicit PersonGallery(const PersonGalleryOptions& options = {}) noexcept;

    /// Adds `personId` (> 0) with `signature`, or replaces their signature. False when the id is
    /// not positive, the signature is empty (no samples) or the gallery is full.
    bool enrol(int personId, const FaceSignature& signature) noexcept;
    void forget(int personId) noexcept;
    void clear() noexcept;
    int size() const noexcept { return count_; }
    bool contains(int personId) const noexcept;

    /// Who `signature` is. A guest (personId 0) when it is empty or nobody scores acceptScore.
    PersonMatch match(const FaceSignature& signature) const noexcept;
    /// The score of `signature` against one enrolled person (0 when unknown).
    float score(int personId, const FaceSignature& signature) const noexcept;

    const PersonGalleryOptions& options() const noexcept { return options_; }
    void setOptions(const PersonGalleryOptions& options) noexcept { options_ = options; }

private:
    struct Entry {
        int personId = 0;
        FaceSignature signature{};
    };
    PersonGalleryOptions options_;
    std::array<Entry, kMaxPeople> entries_{};
    int count_ = 0;
};

}  // namespace vision
