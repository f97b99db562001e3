#pragma once
// The project's overlay models: glasses, sunglasses, hats and face hair, built procedurally.

#include "model.hpp"

#include <vector>

namespace overlaygen {

/// The head the models are made for, in metres, with the eye midpoint as origin (the
/// catalogue's head for a face width of 0.15 m; see assets/overlays/FORMAT.md).
struct HeadMetrics {
    static constexpr double faceWidth = 0.15;
    static constexpr double interocular = 0.063;
    /// The renderer's invisible head proxy (render/head_model.hpp): an ellipsoid whose
    /// horizontal sections are superellipses of this exponent.
    static constexpr double proxyCentre[3] = {0.0, 0.0, -0.0825};
    static constexpr double proxySemiAxes[3] = {0.075, 0.12, 0.093};
    static constexpr double proxySquareness = 3.0;
    /// The head_top anchor.
    static constexpr double headTop[3] = {0.0, 0.12, -0.0825};
    /// The upper_lip and chin anchors (render/head_model.hpp, in metres).
    static constexpr double upperLip[3] = {0.0, -0.051, 0.018};
    static constexpr double chin[3] = {0.0, -0.090, 0.009};
    /// Inner semi-axes of a hat's opening: an ellipse of circumference ~0.57 m.
    static constexpr double hatInnerX = 0.080;
    static constexpr double hatInnerZ = 0.100;
    /// Height of a hat's band line above the eyes.
    static constexpr double hatBaseY = 0.060;
};

Model buildGlasses();
Model buildSunglasses();
Model buildTopHat();
Model buildGraduationCap();
Model buildPartyHat();
Model buildSunHat();
Model buildRainHat();
/// Face hair that follows the fitted face's animation units (face_hair.cpp).
Model buildMoustache();
Model buildGoatee();
/// Hats of the calendar and the weather (seasonal_hats.cpp): a birthday crown with candles, a
/// Santa hat and a knitted winter beanie.
Model buildBirthdayHat();
Model buildSantaHat();
Model buildWinterHat();

/// All of them, in catalogue order.
std::vector<Model> buildAllModels();

}  // namespace overlaygen
