// Seasonal hats for the mirror's calendar and weather: a golden birthday crown with candles (a
// person's birthday). Built like the other hats (models.cpp): closed solids in a hat frame, placed
// on the head by placeHat().

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

}  // namespace overlaygen
