// Face hair: a moustache on the upper lip and a goatee on the chin. Unlike hats and glasses they
// sit on the parts of the face that move as a person talks or smiles, so their catalogue entries
// follow the fitted face's animation units (§5.3's jaw drop, lip stretcher, upper lip raiser):
// the dissertation's future work, "objects that conform to the face as it changes shape".
//
// The follows are CANDIDE-3's own motions (../shared/data/candide3/candide3.wfm) at the head
// model's scale (the mesh 0.735 of the 0.15 m face width wide: 0.090 m per CANDIDE unit): per
// unit of upper lip raiser the upper lip's middle rises 0.065 units (5.9 mm); per unit of lip
// stretcher the mouth corners move out 0.09 units each (0.37 of the half mouth) and the upper lip
// drops 0.022; per unit of jaw drop the chin goes down 0.13-0.26 units and back 0.05-0.15.

#include "models.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace overlaygen {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMetresPerCandideUnit = 0.090;

Model faceHairModel(const std::string& name, const std::string& anchor,
                    const std::string& description)
{
    Model model;
    model.name = name;
    model.kind = "other";
    model.anchor = anchor;
    model.measure = "face_width";
    model.scale = 1.0 / HeadMetrics::faceWidth;
    model.description = description;
    return model;
}

double smoothstep(double edge0, double edge1, double x)
{
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// The moustache's centre line at t in [-1, 1] (x across the lip, the tips curled up), following
// the face's curve back towards the mouth corners.
Vec3 moustachePath(double t)
{
    const double a = std::abs(t);
    const double curl = 0.011 * smoothstep(0.72, 1.0, a);
    return {0.032 * t, 0.001 - 0.007 * t * t + curl, 0.004 - 0.021 * t * t};
}

}  // namespace

Model buildMoustache()
{
    Model model =
        faceHairModel("moustache", "upper_lip",
                      "moustache: a dark handlebar on the upper lip, rising and widening with it");
    const int hair = model.addMaterial("hair", {0.16, 0.10, 0.06, 1.0}, 8.0);
    const int part = model.addPart("moustache", hair);

    // A tube of flattened section along the path, thickest either side of the philtrum and
    // closing to a point at each tip (the grid's end columns collapse into poles).
    constexpr int kAlong = 41, kAround = 10;
    const auto point = [](int i, int j) {
        const double t = -1.0 + 2.0 * i / (kAlong - 1);
        const double dt = 1e-3;
        const Vec3 p = moustachePath(t);
        const Vec3 tangent = (moustachePath(t + dt) - moustachePath(t - dt)).normalized();
        const Vec3 across = Vec3::UnitZ().cross(tangent).normalized();  // mostly up
        const Vec3 depth = tangent.cross(across);                       // mostly out
        const double body = std::pow(std::max(0.0, 1.0 - t * t), 0.6);
        const double parting = 1.0 - 0.3 * std::exp(-(t / 0.07) * (t / 0.07));
        const double height = 0.0064 * body * parting;
        const double v = 2.0 * kPi * j / kAround;
        return Vec3(p + height * std::cos(v) * across + 0.55 * height * std::sin(v) * depth);
    };
    model.solids.push_back(
        gridSolid(kAlong, kAround, false, true, point, [part](int, int) { return part; }));

    const double m = kMetresPerCandideUnit;
    model.follows.push_back({.unit = "upper_lip_raiser", .offset = {0.0, 0.065 * m, 0.0}});
    model.follows.push_back(
        {.unit = "lip_stretcher", .offset = {0.0, -0.022 * m, 0.0}, .stretch = {0.37, 0.0, 0.0}});
    return model;
}

Model buildGoatee()
{
    Model model = faceHairModel("goatee", "chin",
                                "goatee: a pointed tuft on the chin that drops with the jaw");
    const int hair = model.addMaterial("hair", {0.16, 0.10, 0.06, 1.0}, 8.0);
    const int part = model.addPart("goatee", hair);

    // From its point below the chin up to just under the lower lip, flattened front to back.
    const std::vector<Vec2> profile{{0.0, -0.030},   {0.004, -0.025}, {0.008, -0.017},
                                    {0.011, -0.007}, {0.012, 0.003},  {0.010, 0.011},
                                    {0.006, 0.016},  {0.0, 0.018}};
    Solid tuft = lathe(profile, 20, 1.0, 0.45, part);
    tuft.transform(rotationX(-12.0 * kPi / 180.0), Vec3(0.0, 0.0, 0.002));
    model.solids.push_back(tuft);

    const double m = kMetresPerCandideUnit;
    model.follows.push_back({.unit = "jaw_drop", .offset = {0.0, -0.20 * m, -0.09 * m}});
    return model;
}

}  // namespace overlaygen
