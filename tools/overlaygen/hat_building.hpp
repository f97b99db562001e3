#pragma once
// Shared steps of the hats (models.cpp, seasonal_hats.cpp): the catalogue entry of a hat, its
// placement on the head, crown profiles, band sections and fluffy pompoms. Hats are built in a
// hat frame (origin at the centre of the band line, y up, z forward), then placed with placeHat().

#include "model.hpp"

#include <string>
#include <vector>

namespace overlaygen {

/// A hat's model: kind hat, anchor head_top, measure face_width (metres back to catalogue units).
Model hatModel(const std::string& name, const std::string& description);

/// Moves hat-frame solids onto the head: tilt about x (negative: front up, back down), about z
/// (sideways), band centre at (0, hatBaseY + lift, head centre z + back), origin on head_top.
void placeHat(Model& model, double tiltXDegrees, double tiltZDegrees, double lift, double back);

/// A profile (radius, y) from a pole at the bottom centre, out along the bottom, up the side
/// and over a rounded top to the top pole.
std::vector<Vec2> closedProfile(double bottomY, const std::vector<Vec2>& side, double topY);

/// Dome side: superelliptic quarter from (1, 0) to the top, radius normalised.
std::vector<Vec2> domeSide(double height, double exponent, int count, double startY);

/// A hat band's cross-section (radius normalised to the crown, y): a strip standing on the
/// crown from y = 0 to `height` whose top edge leans in, and a third corner inside the crown.
std::vector<Vec2> bandSection(double height, double outside, double topLean);

/// A fluffy pompom: a ball of `around` x `rows` quads whose radius varies by up to `fluff`
/// (relative) with deterministic noise of `seed`; soft normals (no creases).
Solid pompom(const Vec3& centre, double radius, int around, int rows, double fluff, int seed,
             int part);

}  // namespace overlaygen
