#pragma once
// CardTracker: the colour-card tracker (METHOD.md §2), plus what the dissertation lists as future
// work: detecting a lost track and recovering from the trained colour and the shape model,
// sub-pixel corners and temporal smoothing.
//
// A search (no track) tests the whole frame against the trained colour and, for 5 s after the
// card was last tracked, also against the colour it was tracked with then (the light it was lost
// in); a recovered quad must resemble the last one seen whole. While tracking, the shape model
// predicts the next quad: a second seed for step 5, where the card's pieces are, and an edge
// hidden under a hand moves with the card from the last quad measured on all four edges.
//
// train() or setModel() gives it the card's colour; process() then runs steps 2-7 of §2 on every
// frame and reports the card's corners (CardObservation), or lastProblem() says why it found none.
// All buffers are allocated in the constructor for the configured size; process() never allocates
// and never throws.

#include "vision/chromaticity.hpp"
#include "vision/geometry.hpp"
#include "vision/image.hpp"

#include <cstdint>
#include <memory>

namespace vision {

/// The Gaussian colour model in chromaticity (0..255 scale): per channel r, g, b mean and standard
/// deviation. Plain data so the firmware can save and reload it.
struct CardColorModel {
    float mean[3] = {0.f, 0.f, 0.f};
    float sigma[3] = {0.f, 0.f, 0.f};
    bool valid = false;
};

enum class CardState : std::uint8_t {
    Untrained,  ///< no colour model yet: nothing to look for
    Searching,  ///< trained, no card seen yet (or after reset)
    Tracking,   ///< the card is found and its quad is current
    Lost,       ///< the track was lost; searching again from the trained colour and the last shape
};
const char* cardStateName(CardState state) noexcept;

struct CardTrackerOptions {
    float threshold = 3.0f;    ///< t of step 2: |x - mu| < t sigma on each channel
    float minSigma = 8.0f;     ///< floor on sigma (0..255 chromaticity): admits noise and clipping
    float alpha = 0.25f;       ///< a of step 7: weight of the trained model (anchor, no drift)
    float beta = 0.75f;        ///< b of step 7: weight of the previous model (steadiness)
    int changeThreshold = 24;  ///< step 3: |dR|+|dG|+|dB| above this marks a changed pixel
    float minAreaFraction = 0.003f;    ///< a component below this share of the frame is no card
    float maxAreaFraction = 0.85f;     ///< more than this matches: the model ran away -> lost
    int normalsPerEdge = 12;           ///< step 5: sample lines across each edge (first, wide pass)
    float saturationGradient = 0.12f;  ///< step 5: edge where dS exceeds this (S in 0..1)
    float smoothingMinCutoffHz = 1.0f;  ///< One-Euro filter on corners: jitter at rest
    float smoothingBeta = 0.5f;         ///< One-Euro: how fast the cutoff rises with speed (no lag)
    // Added by the implementation (defaults tuned on generated sequences):
    float smoothingDerivativeCutoffHz = 5.0f;  ///< One-Euro: low-pass on the speed estimate
    float frameRateHz = 30.f;     ///< frame interval for the smoothing (process() has no clock)
    float inlierDistance = 1.0f;  ///< step 5: RANSAC inlier band around an edge line (pixels)
    float coarseSearch = 0.12f;   ///< step 5, first pass: walk this x sqrt(quad area) each side
    float fineSearch = 5.f;       ///< step 5, second pass: walk this far each side (pixels)
    int fineNormalsPerEdge = 32;  ///< step 5, second pass: sample lines per edge (short walks)
    float minInlierRatio = 0.3f;  ///< fewer edge inliers per sample line: implausible -> lost
    float maxAspect = 8.f;        ///< longer side / shorter side above this: implausible
    float maxOppositeEdgeRatio = 4.f;   ///< perspective: opposite edges differ more: implausible
    float maxAreaJump = 1.6f;           ///< quad area change per frame (either way) while tracking
    float minFill = 0.3f;               ///< component pixels / quad area below this: implausible
    float maxRecoveryAreaChange = 3.f;  ///< recovery: area within this factor of the last good
    unsigned shapeMemoryFrames = 45;  ///< after this many lost frames any plausible shape recovers
    float chromaticityStep = 0.2f;    ///< step 5: an edge also where chromaticity departs this much
    /// Step 5, beyond §2: when the colour cues find fewer than three edges, an edge also where
    /// brightness departs this much (mean of R, G, B over 255), the fit kept with all four edges
    /// only (card_quad_fit.cpp); 0: never
    float brightnessStep = 0.1f;
};

struct CardObservation {
    CardState state = CardState::Untrained;
    float confidence = 0.f;  ///< 0..1: how sure the tracker is of `quad`
    bool hasQuad = false;    ///< quad is valid (Tracking; also the last good shape while Lost)
    Quad quad{};             ///< smoothed corners, sub-pixel, clockwise from the top-left
    Quad rawQuad{};          ///< corners of this frame before temporal smoothing
    ConstImageView mask;  ///< object mask, Gray8, 255 = card-coloured pixel; until next process()
    int area = 0;         ///< pixels of the largest component
    std::uint32_t framesSinceGood = 0;  ///< frames since the last Tracking frame
};

class CardTracker {
public:
    /// Buffers for frames of `size` (RGB24, BGR24 or XRGB8888 input).
    CardTracker(Size size, const CardTrackerOptions& options = {});
    ~CardTracker();
    CardTracker(const CardTracker&) = delete;
    CardTracker& operator=(const CardTracker&) = delete;

    /// Step 1: trains the colour model on `region` of this frame (the method trains on a frame
    /// where the card fills the view; the appliance trains on a central region). Resets the track.
    /// False (model unchanged) when the region is empty or outside the frame.
    bool train(const ConstImageView& rgb, const ChromaticityPlanes& chroma, Rect region) noexcept;
    /// Installs a saved model (trained earlier). Resets the track.
    void setModel(const CardColorModel& model) noexcept;
    /// Back to untrained: no colour to look for until train() or setModel().
    void forgetModel() noexcept { setModel(CardColorModel{}); }
    const CardColorModel& trainedModel() const noexcept;
    const CardColorModel& currentModel() const noexcept;

    /// Steps 2-7 on one frame. `rgb` is the camera frame, `chroma` its chromaticity planes.
    const CardObservation& process(const ConstImageView& rgb,
                                   const ChromaticityPlanes& chroma) noexcept;
    const CardObservation& observation() const noexcept;
    /// Forgets the track (keeps the model).
    void reset() noexcept;
    /// Why the last frame was not tracked (a static string, "" when it was): e.g. "no component",
    /// "colour model ran away", "quad not convex", "too few edge inliers", "area jump".
    const char* lastProblem() const noexcept;
    const CardTrackerOptions& options() const noexcept;

private:
    struct State;
    std::unique_ptr<State> s_;
};

}  // namespace vision
