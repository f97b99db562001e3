#include "vision/aam_stage.hpp"

#include <algorithm>

namespace vision {

AamStage::AamStage(const MotionStage& motion, const FaceStage& faces, const AamModel& model,
                   const TrackedFaceFitterOptions& options)
    : motion_(motion), faces_(faces), fitter_(model, options)
{
}

void AamStage::process(FrameState& state) noexcept
{
    count_ = 0;
    if (state.valid && motion_.ok()) {
        // The tracker's faces are in the grey image's coordinates: fit there.
        fitter_.process(motion_.gray(), faces_.tracker().faces());
        // Working image -> frame coordinates, as FaceStage converts the faces.
        const float k = static_cast<float>(motion_.downscale());
        const std::span<const FaceFit> fits = fitter_.fits();
        count_ = std::min(fits.size(), fits_.size());
        for (std::size_t i = 0; i < count_; ++i) {
            FaceFit& f = fits_[i];
            f = fits[i];
            f.translation = motion_.toFrame(f.translation);
            f.eyeMidpoint = motion_.toFrame(f.eyeMidpoint);
            f.scale *= k;
            f.faceSize *= k;
            for (int v = 0; v < f.vertexCount; ++v)
                f.vertices[static_cast<std::size_t>(v)] =
                    motion_.toFrame(f.vertices[static_cast<std::size_t>(v)]);
        }
    }
    state.fits = fits();
}

}  // namespace vision
