#include "models.hpp"

#include "hat_building.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <numbers>

namespace overlaygen {

namespace {

constexpr double kPi = std::numbers::pi;

double radians(double degrees)
{
    return degrees * kPi / 180.0;
}

/// x -> -x, keeping the winding outward.
Solid mirroredX(Solid solid)
{
    for (Vec3& p : solid.positions)
        p.x() = -p.x();
    for (Triangle& t : solid.triangles)
        std::swap(t.v[1], t.v[2]);
    return solid;
}

// ---------------------------------------------------------------------------------------------
// Glasses

struct GlassesStyle {
    double lensHalfWidth;
    double lensHalfHeight;
    double lensExponent;  // superellipse: 2 round, larger squarer
    double lensTaper;     // narrower lower half
    double lensCentreX;
    double lensCentreY;
    double wrapDegrees;  // each lens turned so its outer edge goes back
    double frontZ;
    double rimHalfWidth;  // seen from the front
    double rimHalfDepth;
    double bridgeHalfWidth;
    double bridgeRise;
    double armHalfThickness;  // sideways
    double armHalfHeight;
    double hingeX;
    double armX;  // just outside the head proxy (|x| >= 0.078 m)
};

/// Lens plane of the wearer's-left lens (x > 0): centre and rotation.
struct LensFrame {
    Vec3 centre;
    Eigen::Matrix3d rotation;
    Vec3 at(const Vec2& p) const { return centre + rotation * Vec3(p.x(), p.y(), 0.0); }
};

void buildGlassesInto(Model& model, const GlassesStyle& s, int framePart, int templePart,
                      int lensPart)
{
    const LensFrame lens{Vec3(s.lensCentreX, s.lensCentreY, s.frontZ),
                         rotationY(radians(s.wrapDegrees))};
    const int outlinePoints = 24;
    const std::vector<Vec2> outline =
        superellipse(s.lensHalfWidth, s.lensHalfHeight, s.lensExponent, outlinePoints, s.lensTaper);
    // The rim's centre line runs just outside the lens edge, so the lens edge sits in the rim.
    const double grow = 0.5 * s.rimHalfWidth;
    const std::vector<Vec2> rimOutline =
        superellipse(s.lensHalfWidth + grow, s.lensHalfHeight + grow, s.lensExponent, outlinePoints,
                     s.lensTaper);
    const auto rimPoint = [&](double degrees) {
        const std::vector<Vec2> one = superellipse(s.lensHalfWidth + grow, s.lensHalfHeight + grow,
                                                   s.lensExponent, 360, s.lensTaper);
        return lens.at(one[static_cast<std::size_t>(std::lround(degrees)) % 360]);
    };

    // Rims and lenses.
    std::vector<Vec3> rimPath;
    for (const Vec2& p : rimOutline)
        rimPath.push_back(lens.at(p));
    Solid rim = tube(rimPath, true, s.rimHalfWidth, s.rimHalfDepth, lens.rotation * Vec3::UnitZ(),
                     4, framePart);
    Solid lensSolid = prism(outline, 0.0009, lensPart);
    lensSolid.transform(lens.rotation, lens.centre);

    // Bridge: an arch between the upper inner corners of the rims.
    const Vec3 inner = rimPoint(152.0);
    const Vec3 innerRight(-inner.x(), inner.y(), inner.z());
    const Vec3 top(0.0, inner.y() + s.bridgeRise, inner.z() + 0.0015);
    Solid bridge = tube(smoothPath({innerRight, top, inner}, 4), false, s.bridgeHalfWidth,
                        s.rimHalfDepth, Vec3::UnitZ(), 4, framePart);

    // End piece, hinge and temple arm, back along the side of the head and down behind the ear.
    const Vec3 p0 = rimPoint(12.0);
    const double y0 = p0.y();
    const std::vector<Vec3> armControls = {
        p0,
        Vec3(s.hingeX - 0.006, y0 + 0.0015, p0.z() - 0.002),
        Vec3(s.hingeX, y0 + 0.002, p0.z() - 0.010),
        Vec3(s.armX - 0.002, y0 + 0.002, -0.03),
        Vec3(s.armX, y0 + 0.001, -0.07),
        Vec3(s.armX, y0 - 0.002, -0.095),
        // Behind the ear the tip turns in towards the head, where the head hides it.
        Vec3(s.armX - 0.003, y0 - 0.013, -0.110),
        Vec3(s.armX - 0.009, y0 - 0.030, -0.116),
    };
    Solid arm = tube(smoothPath(armControls, 2), false, s.armHalfThickness, s.armHalfHeight,
                     Vec3::UnitY(), 4, templePart);

    model.solids.push_back(rim);
    model.solids.push_back(mirroredX(rim));
    model.solids.push_back(bridge);
    model.solids.push_back(arm);
    model.solids.push_back(mirroredX(arm));
    model.solids.push_back(lensSolid);
    model.solids.push_back(mirroredX(lensSolid));
}

Model glassesModel(const std::string& name, const std::string& description)
{
    Model model;
    model.name = name;
    model.kind = "glasses";
    model.anchor = "eye_midpoint";
    model.measure = "interocular";
    model.scale = 1.0 / HeadMetrics::interocular;
    model.description = description;
    return model;
}

// ---------------------------------------------------------------------------------------------
// Hats: built in a hat frame (origin at the centre of the band line, y up, z forward), then
// tilted and placed on the head with the origin moved to the head_top anchor.

/// A brim around an elliptical opening: at angle theta (0 = front, +90 degrees = wearer's left)
/// and t in [0, 1] from the opening to the edge, the centre surface is
/// ((innerX + t w) sin theta, height(theta, t), (innerZ + t w) cos theta).
struct Brim {
    double innerX;
    double innerZ;
    std::function<double(double theta)> width;
    std::function<double(double theta, double t)> height;
    double thickness;

    Vec3 point(double theta, double t) const
    {
        const double w = width(theta);
        return Vec3((innerX + t * w) * std::sin(theta), height(theta, t),
                    (innerZ + t * w) * std::cos(theta));
    }
};

/// The brim as a closed slab with a rounded outer edge. The top surface (what the camera sees)
/// has `topSteps` rows, the underside, seen only at the edge, `bottomSteps`: every row costs
/// 2 x `segments` triangles in software GL.
Solid brimSolid(const Brim& brim, int segments, int topSteps, int bottomSteps, int part)
{
    // Cross-section loop: top surface outwards, rounded edge, bottom surface inwards.
    const int edgeSteps = 2;  // one point out on the edge: 2-4 pixels thick at 720p
    const int loopCount = (topSteps + 1) + (edgeSteps - 1) + (bottomSteps + 1);
    const double half = 0.5 * brim.thickness;
    return gridSolid(
        segments, loopCount, true, true,
        [&](int i, int j) {
            const double theta = 2.0 * kPi * i / segments;
            if (j <= topSteps) {
                const double t = static_cast<double>(j) / topSteps;
                return Vec3(brim.point(theta, t) + Vec3(0.0, half, 0.0));
            }
            j -= topSteps + 1;
            if (j < edgeSteps - 1) {
                const double phi = kPi * (j + 1) / edgeSteps;
                const Vec3 edge = brim.point(theta, 1.0);
                const Vec3 out = (edge - brim.point(theta, 0.97)).normalized();
                const Vec3 up = Vec3::UnitY();
                return Vec3(edge + out * (half * std::sin(phi)) + up * (half * std::cos(phi)));
            }
            j -= edgeSteps - 1;
            const double t = 1.0 - static_cast<double>(j) / bottomSteps;
            return Vec3(brim.point(theta, t) - Vec3(0.0, half, 0.0));
        },
        [part](int, int) { return part; });
}

}  // namespace

// Hat building steps (hat_building.hpp).

/// Moves hat-frame solids onto the head: tilt about x (negative: front up, back down), about z
/// (sideways), band centre at (0, hatBaseY + lift, head centre z + back), origin on head_top.
void placeHat(Model& model, double tiltXDegrees, double tiltZDegrees, double lift, double back)
{
    const Eigen::Matrix3d rotation =
        rotationZ(radians(tiltZDegrees)) * rotationX(radians(tiltXDegrees));
    const Vec3 band(0.0, HeadMetrics::hatBaseY + lift, HeadMetrics::proxyCentre[2] + back);
    const Vec3 anchor(HeadMetrics::headTop[0], HeadMetrics::headTop[1], HeadMetrics::headTop[2]);
    for (Solid& solid : model.solids)
        solid.transform(rotation, band - anchor);
}

Model hatModel(const std::string& name, const std::string& description)
{
    Model model;
    model.name = name;
    model.kind = "hat";
    model.anchor = "head_top";
    model.measure = "face_width";
    model.scale = 1.0 / HeadMetrics::faceWidth;
    model.description = description;
    return model;
}

/// A profile (radius, y) from a pole at the bottom centre, out along the bottom, up the side
/// r(y) and over a rounded top to the top pole. `side(k)` gives the k-th of `count` points.
std::vector<Vec2> closedProfile(double bottomY, const std::vector<Vec2>& side, double topY)
{
    std::vector<Vec2> profile;
    profile.emplace_back(0.0, bottomY);
    profile.insert(profile.end(), side.begin(), side.end());
    profile.emplace_back(0.0, topY);
    return profile;
}

/// Dome side: superelliptic quarter from (1, 0) to the top, radius normalised.
std::vector<Vec2> domeSide(double height, double exponent, int count, double startY)
{
    std::vector<Vec2> side;
    side.emplace_back(1.0, startY);
    for (int k = 0; k < count; ++k) {
        const double phi = 0.5 * kPi * k / count;
        const double r = std::pow(std::cos(phi), 2.0 / exponent);
        const double y = height * std::pow(std::sin(phi), 2.0 / exponent);
        side.emplace_back(r, y);
    }
    return side;
}

/// A hat band's cross-section (radius normalised to the crown, y): a strip standing on the
/// crown from y = 0 to `height` whose top edge leans in, and a third corner inside the crown
/// (hidden), so a band costs 3 rows of triangles instead of 4.
std::vector<Vec2> bandSection(double height, double outside, double topLean)
{
    return {{outside, 0.001}, {outside * topLean, height}, {0.97, 0.5 * height}};
}

Solid pompom(const Vec3& centre, double radius, int around, int rows, double fluff, int seed,
             int part)
{
    Solid ball = gridSolid(
        around, rows + 1, true, false,
        [&](int i, int j) {
            const double phi = kPi * j / rows - 0.5 * kPi;
            const double theta = 2.0 * kPi * i / around;
            const bool pole = j == 0 || j == rows;
            const double r = radius * (1.0 + (pole ? 0.0 : fluff * hashNoise(i, j, seed)));
            return Vec3(centre.x() + r * std::cos(phi) * std::sin(theta),
                        centre.y() + r * std::sin(phi),
                        centre.z() + r * std::cos(phi) * std::cos(theta));
        },
        [part](int, int) { return part; });
    ball.creaseDegrees = 180.0;  // soft lumps, not crumpled foil
    return ball;
}

// -------------------------------------------------------------------------------------------------

Model buildGlasses()
{
    Model model = glassesModel(
        "glasses", "glasses: thin dark frame (rims, bridge, temple arms), tinted clear lenses");
    const int frame = model.addMaterial("frame", {0.07, 0.06, 0.07, 1.0}, 40.0);
    const int glass = model.addMaterial("lens", {0.35, 0.45, 0.55, 0.12}, 90.0);
    const int rims = model.addPart("frame", frame);
    const int temples = model.addPart("temples", frame);
    const int lenses = model.addPart("lenses", glass);
    const GlassesStyle style{.lensHalfWidth = 0.0245,
                             .lensHalfHeight = 0.0170,
                             .lensExponent = 3.0,
                             .lensTaper = 0.12,
                             .lensCentreX = 0.0335,
                             .lensCentreY = -0.002,
                             .wrapDegrees = 6.0,
                             .frontZ = 0.016,
                             .rimHalfWidth = 0.0014,
                             .rimHalfDepth = 0.0016,
                             .bridgeHalfWidth = 0.0013,
                             .bridgeRise = 0.0035,
                             .armHalfThickness = 0.0010,
                             .armHalfHeight = 0.0017,
                             .hingeX = 0.0700,
                             .armX = 0.0795};
    buildGlassesInto(model, style, rims, temples, lenses);
    return model;
}

Model buildSunglasses()
{
    Model model = glassesModel("sunglasses", "sunglasses: thick glossy black frame, dark lenses");
    const int frame = model.addMaterial("frame", {0.035, 0.035, 0.04, 1.0}, 60.0);
    const int glass = model.addMaterial("lens", {0.05, 0.06, 0.08, 0.9}, 120.0);
    const int rims = model.addPart("frame", frame);
    const int temples = model.addPart("temples", frame);
    const int lenses = model.addPart("lenses", glass);
    const GlassesStyle style{.lensHalfWidth = 0.0275,
                             .lensHalfHeight = 0.0215,
                             .lensExponent = 3.6,
                             .lensTaper = 0.22,
                             .lensCentreX = 0.0355,
                             .lensCentreY = -0.003,
                             .wrapDegrees = 8.0,
                             .frontZ = 0.018,
                             .rimHalfWidth = 0.0036,
                             .rimHalfDepth = 0.0030,
                             .bridgeHalfWidth = 0.0032,
                             .bridgeRise = 0.0015,
                             .armHalfThickness = 0.0018,
                             .armHalfHeight = 0.0045,
                             .hingeX = 0.0720,
                             .armX = 0.0805};
    buildGlassesInto(model, style, rims, temples, lenses);
    return model;
}

Model buildTopHat()
{
    Model model = hatModel("top_hat", "top hat: tall black crown, curled brim, red band");
    const int felt = model.addMaterial("felt", {0.045, 0.045, 0.05, 1.0}, 18.0);
    const int ribbon = model.addMaterial("band", {0.42, 0.05, 0.08, 1.0}, 30.0);
    const int crownPart = model.addPart("crown", felt);
    const int brimPart = model.addPart("brim", felt);
    const int bandPart = model.addPart("band", ribbon);

    const double a = 0.083, b = 0.103, h = 0.165;
    // Slight waist and a flared top, as classic top hats have.
    const auto radius = [&](double y) {
        const double u = y / h;
        return 1.0 - 0.03 * std::sin(kPi * u) + 0.06 * u * u * u;
    };
    std::vector<Vec2> side;
    side.emplace_back(1.0, -0.004);
    // The waist and flare are gentle: 5 rows follow them; the crown's 32 segments keep the
    // silhouette within a pixel at 720p.
    const int rows = 5;
    for (int k = 0; k <= rows; ++k) {
        const double y = (h - 0.004) * k / rows;
        side.emplace_back(radius(y), y);
    }
    const double topR = radius(h);
    side.emplace_back(topR - 0.015, h);  // a bevelled top edge
    model.solids.push_back(lathe(closedProfile(-0.004, side, h), 32, a, b, crownPart));

    model.solids.push_back(latheLoop(bandSection(0.036, 1.022, 0.995), 32, a, b, bandPart));

    const Brim brim{
        .innerX = 0.076,
        .innerZ = 0.096,
        .width = [](double theta) { return 0.052 - 0.006 * std::pow(std::cos(theta), 2); },
        .height =
            [](double theta, double t) {
                const double u = std::max(0.0, (t - 0.12) / 0.88);
                const double s = std::sin(theta), c = std::cos(theta);
                return 0.026 * s * s * u * u - 0.005 * c * c * u * u;
            },
        .thickness = 0.004};
    model.solids.push_back(brimSolid(brim, 48, 3, 2, brimPart));
    placeHat(model, -4.0, 0.0, -0.006, 0.0);
    return model;
}

Model buildGraduationCap()
{
    Model model =
        hatModel("graduation_cap", "graduation cap: black mortarboard on a skull cap, gold tassel");
    const int cloth = model.addMaterial("cloth", {0.06, 0.06, 0.07, 1.0}, 6.0);
    const int gold = model.addMaterial("tassel", {0.88, 0.66, 0.16, 1.0}, 30.0);
    const int capPart = model.addPart("cap", cloth);
    const int boardPart = model.addPart("board", cloth);
    const int tasselPart = model.addPart("tassel", gold);

    const double a = 0.083, b = 0.103;
    const std::vector<Vec2> side = {
        {1.0, -0.003}, {1.0, 0.014}, {0.975, 0.038}, {0.90, 0.058}, {0.74, 0.072}};
    model.solids.push_back(lathe(closedProfile(-0.003, side, 0.077), 32, a, b, capPart));

    const double boardY = 0.079, half = 0.003;
    Solid board = box(Vec3(0.121, 0.121, half), boardPart);
    board.transform(rotationX(radians(-90.0)), Vec3(0.0, boardY, 0.0));
    model.solids.push_back(board);

    const double topY = boardY + half;
    Solid button = ellipsoid(Vec3(0.009, 0.004, 0.009), 12, 4, tasselPart);
    button.transform(Eigen::Matrix3d::Identity(), Vec3(0.0, topY + 0.001, 0.0));
    model.solids.push_back(button);

    // The cord runs from the button over the board to the wearer's right edge, and hangs.
    const double edgeX = -0.1235, cordZ = 0.065, cord = 0.0014;
    const std::vector<Vec3> cordControls = {
        {0.0, topY + 0.002, 0.0},
        {-0.06, topY + cord, 0.032},
        {-0.112, topY + cord, 0.060},
        {edgeX, topY - 0.001, cordZ},
        {edgeX - 0.001, topY - 0.015, cordZ},
        {edgeX - 0.001, -0.005, cordZ},
    };
    model.solids.push_back(
        tube(smoothPath(cordControls, 3), false, cord, cord, Vec3::UnitZ(), 4, tasselPart));
    // Tassel: a knot and a fluted, flaring bundle of threads.
    Solid knot = ellipsoid(Vec3(0.0055, 0.0065, 0.0055), 8, 4, tasselPart);
    knot.transform(Eigen::Matrix3d::Identity(), Vec3(edgeX - 0.001, -0.008, cordZ));
    model.solids.push_back(knot);
    const int around = 16, rows = 5;
    const double tasselTop = -0.010, tasselLength = 0.055;
    Solid threads = gridSolid(
        around, rows + 2, true, false,
        [&](int i, int j) {
            const double theta = 2.0 * kPi * i / around;
            const Vec3 centre(edgeX - 0.001, 0.0, cordZ);
            if (j == 0)
                return Vec3(centre + Vec3(0.0, tasselTop, 0.0));
            if (j == rows + 1)
                return Vec3(centre + Vec3(0.0, tasselTop - tasselLength, 0.0));
            const double u = static_cast<double>(j - 1) / (rows - 1);
            const double r = (0.0035 + 0.0065 * std::pow(u, 1.5)) * (i % 2 == 0 ? 1.0 : 0.8);
            return Vec3(centre + Vec3(r * std::sin(theta), tasselTop - tasselLength * u,
                                      r * std::cos(theta)));
        },
        [tasselPart](int, int) { return tasselPart; });
    threads.creaseDegrees = 60.0;
    model.solids.push_back(threads);

    placeHat(model, 5.0, 0.0, -0.006, 0.0);
    return model;
}

Model buildPartyHat()
{
    Model model =
        hatModel("party_hat", "party hat: cone with spiral stripes, pompom, ruffled trim");
    const int pink = model.addMaterial("stripe_pink", {0.92, 0.16, 0.52, 1.0}, 25.0);
    const int yellow = model.addMaterial("stripe_yellow", {1.0, 0.84, 0.12, 1.0}, 25.0);
    const int white = model.addMaterial("pompom", {0.97, 0.97, 0.95, 1.0}, 0.0);
    const int cyan = model.addMaterial("trim", {0.10, 0.72, 0.90, 1.0}, 20.0);
    const int pinkPart = model.addPart("stripes_pink", pink, "cone");
    const int yellowPart = model.addPart("stripes_yellow", yellow, "cone");
    const int pompomPart = model.addPart("pompom", white);
    const int trimPart = model.addPart("trim", cyan);

    const double radius = 0.062, height = 0.18;
    const int around = 48, rows = 8, stripeColumns = 4;
    const double twist = 2.7;  // columns of shift per row: the stripes spiral up
    // Rows: 0 base centre, 1..rows+1 the cone from the base ring (t = 0) to the tip (t = 1).
    Solid cone = gridSolid(
        around, rows + 2, true, false,
        [&](int i, int j) {
            if (j == 0)
                return Vec3(0.0, 0.0, 0.0);
            const double t = static_cast<double>(j - 1) / rows;
            const double theta = 2.0 * kPi * (i + twist * (j - 1)) / around;
            const double r = radius * (1.0 - t);
            return Vec3(r * std::sin(theta), height * t, r * std::cos(theta));
        },
        [&](int i, int) { return (i / stripeColumns) % 2 == 0 ? pinkPart : yellowPart; });
    cone.creaseDegrees = 50.0;
    model.solids.push_back(cone);

    // Pompom: a ball with a fluffy, randomly bumpy surface.
    model.solids.push_back(
        pompom(Vec3(0.0, height - 0.004, 0.0), 0.019, 14, 8, 0.09, 7, pompomPart));

    // Ruffled trim around the base: a tube whose radius waves around the cone.
    std::vector<Vec3> ring;
    const int ruffles = 12, ringPoints = 4 * ruffles;
    for (int k = 0; k < ringPoints; ++k) {
        const double theta = 2.0 * kPi * k / ringPoints;
        const double wave = ruffles * theta;
        const double r = radius + 0.003 + 0.0024 * std::sin(wave);
        ring.emplace_back(r * std::sin(theta), 0.004 + 0.0015 * std::cos(wave),
                          r * std::cos(theta));
    }
    model.solids.push_back(tube(ring, true, 0.0045, 0.0045, Vec3::UnitY(), 5, trimPart));

    // Sits on the crown, a little to the side for fun.
    const Eigen::Matrix3d rotation = rotationZ(radians(-12.0)) * rotationX(radians(-6.0));
    const Vec3 base(0.006, 0.088, HeadMetrics::proxyCentre[2] + 0.008);
    const Vec3 anchor(HeadMetrics::headTop[0], HeadMetrics::headTop[1], HeadMetrics::headTop[2]);
    for (Solid& solid : model.solids)
        solid.transform(rotation, base - anchor);
    return model;
}

Model buildSunHat()
{
    Model model = hatModel("sun_hat", "sun hat: straw, wide soft brim, rounded crown, ribbon");
    const int straw = model.addMaterial("straw", {0.87, 0.75, 0.50, 1.0}, 0.0);
    const int navy = model.addMaterial("ribbon", {0.12, 0.18, 0.52, 1.0}, 30.0);
    const int crownPart = model.addPart("crown", straw);
    const int brimPart = model.addPart("brim", straw);
    const int ribbonPart = model.addPart("ribbon", navy);

    const double a = 0.086, b = 0.106, h = 0.098;
    const std::vector<Vec2> side = domeSide(h, 2.6, 5, -0.004);
    model.solids.push_back(lathe(closedProfile(-0.004, side, h), 32, a, b, crownPart));

    const double bandOut = 1.025;
    model.solids.push_back(latheLoop(bandSection(0.026, bandOut, 0.99), 32, a, b, ribbonPart));

    const Brim brim{.innerX = 0.079,
                    .innerZ = 0.099,
                    .width = [](double theta) { return 0.100 + 0.012 * std::cos(theta); },
                    .height =
                        [](double theta, double t) {
                            // Droops softly, a little less at the front, with gentle waves.
                            // (a flatter back hides behind the head instead of hanging below it)
                            const double droop =
                                (0.026 + 0.008 * std::cos(theta)) * std::pow(t, 1.6);
                            const double wave = 0.009 * t * t * std::sin(5.0 * theta + 0.4);
                            return -droop + wave;
                        },
                    .thickness = 0.004};
    model.solids.push_back(brimSolid(brim, 44, 3, 2, brimPart));

    // A bow on the ribbon at the wearer's right, a little behind the side.
    const double theta = radians(-110.0);
    const Vec3 outward = Vec3(std::sin(theta) / a, 0.0, std::cos(theta) / b).normalized();
    const Vec3 along = Vec3::UnitY().cross(outward).normalized();
    Eigen::Matrix3d frame;
    frame.col(0) = along;
    frame.col(1) = Vec3::UnitY();
    frame.col(2) = outward;
    const Vec3 knotAt(bandOut * a * std::sin(theta), 0.0135, bandOut * b * std::cos(theta));
    for (int sideSign : {-1, 1}) {
        Solid loop = ellipsoid(Vec3(0.021, 0.011, 0.005), 8, 4, ribbonPart);
        loop.transform(frame * rotationZ(radians(12.0 * sideSign)),
                       knotAt + outward * 0.005 + along * (0.019 * sideSign));
        model.solids.push_back(loop);
        Solid tail = box(Vec3(0.006, 0.024, 0.0012), ribbonPart);
        tail.transform(
            frame * rotationZ(radians(18.0 * sideSign)),
            knotAt + outward * 0.006 + along * (0.008 * sideSign) + Vec3(0.0, -0.016, 0.0));
        model.solids.push_back(tail);
    }
    Solid knot = ellipsoid(Vec3(0.007, 0.009, 0.006), 8, 4, ribbonPart);
    knot.transform(frame, knotAt + outward * 0.007);
    model.solids.push_back(knot);

    placeHat(model, -3.0, 0.0, -0.004, 0.0);
    return model;
}

Model buildRainHat()
{
    Model model =
        hatModel("rain_hat", "rain hat (sou'wester): yellow oilskin, brim long at the back, seams");
    const int oilskin = model.addMaterial("oilskin", {1.0, 0.80, 0.06, 1.0}, 50.0);
    const int seam = model.addMaterial("seams", {0.78, 0.56, 0.02, 1.0}, 30.0);
    const int crownPart = model.addPart("crown", oilskin);
    const int brimPart = model.addPart("brim", oilskin);
    const int seamPart = model.addPart("seams", seam);

    const double a = 0.086, b = 0.106, h = 0.086;
    const std::vector<Vec2> side = domeSide(h, 2.4, 5, -0.004);
    model.solids.push_back(lathe(closedProfile(-0.004, side, h), 32, a, b, crownPart));

    // Six panel seams over the crown, meeting at the top.
    for (int k = 0; k < 6; ++k) {
        const double theta = 2.0 * kPi * k / 6.0 + kPi / 6.0;
        std::vector<Vec3> path;
        for (std::size_t p = 1; p < side.size(); ++p) {
            const Vec2& q = side[p];
            const double grow = 1.0 + 0.012;
            path.emplace_back(q.x() * a * grow * std::sin(theta), q.y() + 0.0008 * q.y() / h,
                              q.x() * b * grow * std::cos(theta));
        }
        path.emplace_back(0.0, h + 0.0008, 0.0);
        model.solids.push_back(tube(path, false, 0.0013, 0.0013,
                                    Vec3(std::cos(theta), 0.0, -std::sin(theta)), 3, seamPart));
    }

    const Brim brim{.innerX = 0.080,
                    .innerZ = 0.100,
                    // Short at the front and sides, long right at the back to shed the rain
                    // off the neck (where the head hides it from the front).
                    .width =
                        [](double theta) {
                            const double back = 0.5 * (1.0 - std::cos(theta));
                            return 0.048 + 0.065 * std::pow(back, 3.5);
                        },
                    .height =
                        [](double theta, double t) {
                            // Turned down all round, steeply at the back.
                            const double back = 0.5 * (1.0 - std::cos(theta));
                            return -(0.024 + 0.050 * back * back * back) * std::pow(t, 1.1);
                        },
                    .thickness = 0.0045};
    model.solids.push_back(brimSolid(brim, 40, 2, 1, brimPart));
    // A stitched line around the brim and one where the brim meets the crown.
    for (double t : {0.0, 0.78}) {
        std::vector<Vec3> ring;
        for (int k = 0; k < 32; ++k) {
            const double theta = 2.0 * kPi * k / 32.0;
            Vec3 p = brim.point(theta, t) + Vec3(0.0, 0.5 * brim.thickness + 0.0006, 0.0);
            if (t == 0.0)  // the crown's foot
                p = Vec3(1.012 * a * std::sin(theta), 0.004, 1.012 * b * std::cos(theta));
            ring.push_back(p);
        }
        model.solids.push_back(tube(ring, true, 0.0014, 0.0014, Vec3::UnitY(), 3, seamPart));
    }

    placeHat(model, -3.0, 0.0, -0.008, 0.0);
    return model;
}

std::vector<Model> buildAllModels()
{
    return {buildGlasses(),  buildSunglasses(),  buildTopHat(),   buildGraduationCap(),
            buildPartyHat(), buildSunHat(),      buildRainHat(),  buildMoustache(),
            buildGoatee(),   buildBirthdayHat(), buildSantaHat(), buildWinterHat()};
}

}  // namespace overlaygen
