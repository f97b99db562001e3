// Seasonal hats for the mirror's calendar and weather: a golden birthday crown with candles (a
// person's birthday), a Santa hat (Christmas) and a knitted winter beanie (snow). Built like the
// other hats (models.cpp): closed solids in a hat frame, placed on the head by placeHat().

#include "hat_building.hpp"
#include "models.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace overlaygen {

namespace {

constexpr double kPi = std::numbers::pi;

/// The point of an elliptical ring of normalised radius r at angle theta (0 = front, +x left).
Vec3 around(double theta, double r, double y, double a, double b)
{
    return {r * a * std::sin(theta), y, r * b * std::cos(theta)};
}

}  // namespace

Model buildBirthdayHat()
{
    Model model = hatModel("birthday_hat",
                           "birthday crown: golden paper crown with eight points, a candle "
                           "burning on each point, jewels on the band");
    const int gold = model.addMaterial("gold", {0.96, 0.74, 0.20, 1.0}, 60.0);
    const int pink = model.addMaterial("candle_pink", {0.98, 0.45, 0.68, 1.0}, 20.0);
    const int blue = model.addMaterial("candle_blue", {0.38, 0.70, 0.98, 1.0}, 20.0);
    const int fire = model.addMaterial("flame", {1.0, 0.80, 0.22, 1.0}, 0.0);
    const int ruby = model.addMaterial("ruby", {0.80, 0.06, 0.16, 1.0}, 90.0);
    const int sapphire = model.addMaterial("sapphire", {0.10, 0.22, 0.85, 1.0}, 90.0);
    const int crownPart = model.addPart("crown", gold);
    const int pinkPart = model.addPart("candles_pink", pink);
    const int bluePart = model.addPart("candles_blue", blue);
    const int flamePart = model.addPart("flames", fire);
    const int rubyPart = model.addPart("rubies", ruby);
    const int sapphirePart = model.addPart("sapphires", sapphire);

    // The crown: a thin wall around the head flaring a little towards its top, whose top edge
    // rises to a point every 4 of its 32 columns (a point in front).
    const double a = 0.084, b = 0.104;
    const int points = 8, perPoint = 4, columns = points * perPoint;
    const double valley = 0.030, tip = 0.066, bottom = -0.004, wall = 0.022;  // wall: normalised
    const auto flare = [&](double y) { return 1.0 + 0.05 * std::max(0.0, y) / tip; };
    const auto top = [&](int i) {
        const double f = std::abs(static_cast<double>(i % perPoint) / (0.5 * perPoint) - 1.0);
        return valley + (tip - valley) * std::pow(f, 1.3);
    };
    Solid crown = gridSolid(
        columns, 4, true, true,
        [&](int i, int j) {
            const double theta = 2.0 * kPi * i / columns;
            const double y = (j == 0 || j == 3) ? bottom : top(i);
            const double r = (j < 2 ? 1.0 : 1.0 - wall) * flare(y);
            return around(theta, r, y, a, b);
        },
        [crownPart](int, int) { return crownPart; });
    model.solids.push_back(crown);

    for (int k = 0; k < points; ++k) {
        const double theta = 2.0 * kPi * k / points;
        const double r = (1.0 - 0.5 * wall) * flare(tip);
        // A candle stands on each point, sunk a little into the paper, its flame above the wick.
        const Vec3 foot = around(theta, r, tip - 0.004, a, b);
        const double candleHeight = 0.024, candleRadius = 0.0045;
        Solid candle = lathe({{0.0, 0.0},
                              {candleRadius, 0.0},
                              {candleRadius, candleHeight},
                              {0.0, candleHeight + 0.0008}},
                             8, 1.0, 1.0, k % 2 == 0 ? pinkPart : bluePart);
        candle.transform(Eigen::Matrix3d::Identity(), foot);
        model.solids.push_back(candle);
        Solid flame = lathe({{0.0, 0.0}, {0.0033, 0.0042}, {0.0026, 0.0098}, {0.0, 0.0175}}, 6, 1.0,
                            1.0, flamePart);
        flame.transform(Eigen::Matrix3d::Identity(), foot + Vec3(0.0, candleHeight + 0.0018, 0.0));
        model.solids.push_back(flame);

        // A jewel on the band under each point, alternately ruby and sapphire, facing out.
        const Vec3 outward = Vec3(std::sin(theta) / a, 0.0, std::cos(theta) / b).normalized();
        Eigen::Matrix3d frame;
        frame.col(2) = outward;
        frame.col(1) = Vec3::UnitY();
        frame.col(0) = Vec3::UnitY().cross(outward).normalized();
        Solid jewel = prism({{0.0058, 0.0}, {0.0, 0.0078}, {-0.0058, 0.0}, {0.0, -0.0078}}, 0.0015,
                            k % 2 == 0 ? rubyPart : sapphirePart);
        const double jewelY = 0.014;
        jewel.transform(frame, around(theta, flare(jewelY), jewelY, a, b) + 0.0006 * outward);
        model.solids.push_back(jewel);
    }

    placeHat(model, -3.0, 0.0, 0.002, 0.0);
    return model;
}

Model buildSantaHat()
{
    Model model = hatModel(
        "santa_hat", "Santa hat: red cone flopping to the wearer's right, white fur band, pompom");
    const int red = model.addMaterial("velvet", {0.78, 0.05, 0.08, 1.0}, 12.0);
    const int white = model.addMaterial("fur", {0.97, 0.97, 0.95, 1.0}, 0.0);
    const int conePart = model.addPart("cone", red, "cone");
    // The cone's flat bottom in the fur's colour: seen from below it passes for the band's inside.
    const int liningPart = model.addPart("lining", white, "cone");
    const int furPart = model.addPart("fur", white);
    const int pompomPart = model.addPart("pompom", white);

    // The cone: rings along a centre line that rises from the band, bends over the top of the
    // head and hangs down beside it; the rings shrink to the tip.
    const double a = 0.084, b = 0.104;
    const std::vector<Vec3> line = smoothPath({{0.0, 0.0, 0.0},
                                               {0.0, 0.050, -0.004},
                                               {-0.012, 0.098, -0.010},
                                               {-0.052, 0.128, -0.012},
                                               {-0.098, 0.112, -0.008},
                                               {-0.126, 0.046, -0.002}},
                                              2);
    const int segments = 24, rings = static_cast<int>(line.size());
    Solid cone = gridSolid(
        segments, rings + 1, true, false,
        [&](int i, int j) {
            if (j == 0)
                return Vec3(0.0, 0.0, 0.0);
            const int k = j - 1;
            const double t = static_cast<double>(k) / (rings - 1);
            const Vec3& c = line[static_cast<std::size_t>(k)];
            const Vec3 tangent = (line[static_cast<std::size_t>(std::min(k + 1, rings - 1))] -
                                  line[static_cast<std::size_t>(std::max(k - 1, 0))])
                                     .normalized();
            const Vec3 side = tangent.cross(Vec3::UnitZ()).normalized();
            const Vec3 depth = side.cross(tangent);
            const double shrink = std::pow(1.0 - t, 1.35);
            // Elliptical like the head at the band, round further up.
            const double rx = shrink * (a + (0.5 * (a + b) - a) * t);
            const double rz = shrink * (b + (0.5 * (a + b) - b) * t);
            const double theta = 2.0 * kPi * i / segments;
            return Vec3(c + rx * std::sin(theta) * side + rz * std::cos(theta) * depth);
        },
        [&](int, int j) { return j == 0 ? liningPart : conePart; });
    model.solids.push_back(cone);

    // The fur band: a thick bumpy roll around the cone's foot (its inner side hidden in it).
    const std::vector<Vec2> section = {
        {0.96, -0.004}, {1.09, -0.010}, {1.15, 0.010}, {1.10, 0.031}, {0.97, 0.035}};
    const int furAround = 36;
    Solid fur = gridSolid(
        furAround, static_cast<int>(section.size()), true, true,
        [&](int i, int j) {
            const Vec2& s = section[static_cast<std::size_t>(j)];
            const bool outside = j >= 1 && j <= 3;
            const double r = s.x() * (outside ? 1.0 + 0.035 * hashNoise(i, j, 23) : 1.0);
            const double y = s.y() + (outside ? 0.002 * hashNoise(i, j, 29) : 0.0);
            return around(2.0 * kPi * i / furAround, r, y, a, b);
        },
        [furPart](int, int) { return furPart; });
    fur.creaseDegrees = 180.0;
    model.solids.push_back(fur);

    model.solids.push_back(
        pompom(line.back() + Vec3(-0.004, -0.010, 0.0), 0.025, 12, 7, 0.10, 31, pompomPart));

    placeHat(model, -4.0, 0.0, -0.002, 0.0);
    return model;
}

Model buildWinterHat()
{
    Model model = hatModel("winter_hat",
                           "winter hat: knitted beanie, ribbed folded cuff, two cream stripes, "
                           "pompom");
    const int wool = model.addMaterial("wool", {0.10, 0.33, 0.56, 1.0}, 0.0);
    const int cream = model.addMaterial("wool_cream", {0.94, 0.90, 0.80, 1.0}, 0.0);
    const int domeBlue = model.addPart("dome", wool, "dome");
    const int domeCream = model.addPart("stripes", cream, "dome");
    const int cuffPart = model.addPart("cuff", wool);
    const int pompomPart = model.addPart("pompom", cream);

    // The dome hugs the head, smooth (its ribs would be facets at 32 columns); the cuff is ribbed.
    const double a = 0.085, b = 0.104, h = 0.104, domeFoot = 0.026;
    const int segments = 32, rows = 7;
    std::vector<Vec2> profile = {{0.0, -0.002}, {0.985, -0.002}};
    for (int k = 0; k <= rows; ++k) {
        const double phi = 0.5 * kPi * k / rows;
        const double e = 2.2;
        profile.emplace_back(k == rows ? 0.0 : std::pow(std::cos(phi), 2.0 / e),
                             domeFoot + (h - domeFoot) * std::pow(std::sin(phi), 2.0 / e));
    }
    const int n = static_cast<int>(profile.size());
    Solid dome = gridSolid(
        segments, n, true, false,
        [&](int i, int j) {
            const Vec2& p = profile[static_cast<std::size_t>(j)];
            return around(2.0 * kPi * i / segments, p.x(), p.y(), a, b);
        },
        // Quad rows: 0 bottom, 1 inside the cuff, 2.. the dome from its foot; rows 3 and 5
        // are the cream stripes.
        [&](int, int j) { return j == 3 || j == 5 ? domeCream : domeBlue; });
    dome.creaseDegrees = 60.0;
    model.solids.push_back(dome);

    // The folded cuff: a thick ring, ribbed by 20 ribs (alternate columns out and in; faces of
    // neighbouring columns meet at ~20 degrees and keep their own normals, so the per-vertex
    // light shows the ribs as stripes).
    const std::vector<Vec2> section = {
        {0.975, -0.012}, {1.055, -0.013}, {1.075, 0.026}, {1.0, 0.034}};
    const int cuffAround = 40;
    Solid cuff = gridSolid(
        cuffAround, static_cast<int>(section.size()), true, true,
        [&](int i, int j) {
            const Vec2& s = section[static_cast<std::size_t>(j)];
            const double rib = (j == 1 || j == 2) ? 1.0 + (i % 2 == 0 ? 0.018 : -0.014) : 1.0;
            return around(2.0 * kPi * i / cuffAround, s.x() * rib, s.y(), a, b);
        },
        [cuffPart](int, int) { return cuffPart; });
    cuff.creaseDegrees = 12.0;
    model.solids.push_back(cuff);

    model.solids.push_back(
        pompom(Vec3(0.0, h + 0.020, -0.004), 0.028, 12, 7, 0.12, 37, pompomPart));

    placeHat(model, -5.0, 0.0, -0.013, 0.0);
    return model;
}

}  // namespace overlaygen
