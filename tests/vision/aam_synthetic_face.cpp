// Synthetic faces for the AAM fit (aam_synthetic_face.hpp): the head projected as AamHead
// documents it, each image pixel inside a projected triangle mapped back into the mean shape's
// frame by its barycentric coordinates and given the model's appearance there (bilinear), nearest
// triangle wins (depth-tested), the rest a smooth random background with a little noise.
#include "aam_synthetic_face.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace aam_test {

void drawFace(const vision::AamModel& m, const SyntheticFaceSpec& spec,
              const std::vector<Eigen::Vector3f>& placed, vision::ImageView img);

namespace {

/// The model's appearance on the whole frame grid: model pixels as the model says, the others
/// filled outward from their neighbours (so bilinear sampling near the border has values).
std::vector<float> denseAppearance(const vision::AamModel& m, const std::vector<float>& weights)
{
    const int w = m.frameWidth, h = m.frameHeight;
    std::vector<float> grid(static_cast<std::size_t>(w) * h, std::nanf(""));
    for (std::size_t i = 0; i < m.pixels.size(); ++i) {
        float v = m.meanAppearance[i];
        for (std::size_t k = 0; k < weights.size() && k < m.appearanceModeCount(); ++k)
            v += weights[k] * std::sqrt(m.appearanceVariances[k]) *
                 m.appearanceModes[k * m.pixels.size() + i];
        grid[static_cast<std::size_t>(m.pixels[i].y) * w + m.pixels[i].x] = v;
    }
    for (int round = 0; round < 3; ++round) {
        std::vector<float> next = grid;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                if (!std::isnan(grid[static_cast<std::size_t>(y) * w + x]))
                    continue;
                float sum = 0;
                int n = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int u = x + dx, v = y + dy;
                        if (u < 0 || v < 0 || u >= w || v >= h)
                            continue;
                        const float g = grid[static_cast<std::size_t>(v) * w + u];
                        if (!std::isnan(g)) {
                            sum += g;
                            ++n;
                        }
                    }
                if (n > 0)
                    next[static_cast<std::size_t>(y) * w + x] = sum / static_cast<float>(n);
            }
        }
        grid = next;
    }
    for (float& g : grid)
        g = std::isnan(g) ? 0.f : g;
    return grid;
}

float sampleBilinear(const std::vector<float>& grid, int w, int h, float x, float y)
{
    x = std::clamp(x, 0.f, static_cast<float>(w - 1) - 1e-3f);
    y = std::clamp(y, 0.f, static_cast<float>(h - 1) - 1e-3f);
    const int ix = static_cast<int>(x), iy = static_cast<int>(y);
    const float fx = x - static_cast<float>(ix), fy = y - static_cast<float>(iy);
    const auto at = [&](int u, int v) { return grid[static_cast<std::size_t>(v) * w + u]; };
    return (1 - fy) * ((1 - fx) * at(ix, iy) + fx * at(ix + 1, iy)) +
           fy * ((1 - fx) * at(ix, iy + 1) + fx * at(ix + 1, iy + 1));
}

void drawBackground(vision::ImageView img, std::uint32_t seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> phase(0.f, 6.283f), freq(0.01f, 0.06f);
    std::normal_distribution<float> noise(0.f, 3.f);
    float fx[3], fy[3], ph[3];
    for (int k = 0; k < 3; ++k) {
        fx[k] = freq(random);
        fy[k] = freq(random);
        ph[k] = phase(random);
    }
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            float v = 110.f + noise(random);
            for (int k = 0; k < 3; ++k)
                v += 25.f * std::sin(fx[k] * static_cast<float>(x) + fy[k] * static_cast<float>(y) +
                                     ph[k]);
            img.row(y)[x] = static_cast<std::uint8_t>(std::clamp(v, 0.f, 255.f));
        }
}

}  // namespace

SyntheticFace renderShape(const vision::AamModel& m, const SyntheticFaceSpec& spec,
                          const std::vector<vision::Point2f>& shape, int width, int height)
{
    SyntheticFace face;
    face.image = vision::ImageBuffer(width, height, vision::PixelFormat::Gray8);
    drawBackground(face.image.view(), spec.backgroundSeed);
    std::vector<Eigen::Vector3f> placed;
    for (const vision::Point2f& p : shape)
        placed.emplace_back(p.x, p.y, 0.f);
    face.vertices = shape;
    drawFace(m, spec, placed, face.image.view());
    return face;
}

vision::AamStart SyntheticFace::box(float rollDegrees) const
{
    float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
    for (const vision::Point2f& p : vertices) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    return {{0.5f * (x0 + x1), 0.5f * (y0 + y1)}, x1 - x0, rollDegrees};
}

vision::AamHead meanShapeHead(const vision::AamModel& m)
{
    const int v = static_cast<int>(m.mesh.vertices.size());
    const int units = vision::kAamShapeUnits + vision::kAamAnimationUnits;
    Eigen::MatrixXd unitX = Eigen::MatrixXd::Zero(v, units), unitY = unitX;
    int column = 0;
    for (const auto* list : {&m.mesh.shapeUnits, &m.mesh.animationUnits})
        for (const vision::CandideUnit& u : *list) {
            for (std::size_t k = 0; k < u.vertices.size(); ++k) {
                unitX(u.vertices[k], column) += u.displacements[k].x();
                unitY(u.vertices[k], column) += u.displacements[k].y();
            }
            ++column;
        }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(units);
    double tx = 0, ty = 0, a = 1, b = 0;
    for (int round = 0; round < 20; ++round) {
        // The similarity with the units fixed: image = t + (a gx + b gy, b gx - a gy).
        Eigen::MatrixXd A(2 * v, 4);
        Eigen::VectorXd y(2 * v);
        for (int i = 0; i < v; ++i) {
            const double gx =
                m.mesh.vertices[static_cast<std::size_t>(i)].x() + unitX.row(i).dot(x);
            const double gy =
                m.mesh.vertices[static_cast<std::size_t>(i)].y() + unitY.row(i).dot(x);
            A.row(2 * i) << 1, 0, gx, gy;
            A.row(2 * i + 1) << 0, 1, -gy, gx;
            y(2 * i) = m.meanShape[2 * static_cast<std::size_t>(i)];
            y(2 * i + 1) = m.meanShape[2 * static_cast<std::size_t>(i) + 1];
        }
        const Eigen::Vector4d s = A.colPivHouseholderQr().solve(y);
        tx = s(0), ty = s(1), a = s(2), b = s(3);
        // The units with the similarity fixed, a weak ridge as the builder's.
        Eigen::MatrixXd B(2 * v, units);
        for (int i = 0; i < v; ++i) {
            const Eigen::Vector3f& g = m.mesh.vertices[static_cast<std::size_t>(i)];
            B.row(2 * i) = a * unitX.row(i) + b * unitY.row(i);
            B.row(2 * i + 1) = b * unitX.row(i) - a * unitY.row(i);
            y(2 * i) -= tx + a * g.x() + b * g.y();
            y(2 * i + 1) -= ty + b * g.x() - a * g.y();
        }
        const double ridge = std::pow(0.02 * std::hypot(a, b), 2);
        Eigen::MatrixXd normal = B.transpose() * B;
        normal.diagonal().array() += ridge;
        x = normal.ldlt().solve(B.transpose() * y);
    }
    vision::AamHead head;
    for (int i = 0; i < vision::kAamShapeUnits; ++i)
        head.sigma[static_cast<std::size_t>(i)] = static_cast<float>(x(i));
    for (int i = 0; i < vision::kAamAnimationUnits; ++i)
        head.tau[static_cast<std::size_t>(i)] = static_cast<float>(x(vision::kAamShapeUnits + i));
    return head;
}

float meshWidthUnits(const vision::AamModel& model)
{
    float low = 1e9f, high = -1e9f;
    for (const Eigen::Vector3f& v : model.mesh.vertices) {
        low = std::min(low, v.x());
        high = std::max(high, v.x());
    }
    return high - low;
}

SyntheticFace renderSyntheticFace(const vision::AamModel& m, const SyntheticFaceSpec& spec,
                                  int width, int height)
{
    SyntheticFace face;
    face.image = vision::ImageBuffer(width, height, vision::PixelFormat::Gray8);
    vision::ImageView img = face.image.view();
    drawBackground(img, spec.backgroundSeed);

    // The head: g = g0 + S sigma + A tau, turned by pitch * yaw, flipped, rolled, scaled, moved.
    std::vector<float> sigma(spec.head.sigma.begin(), spec.head.sigma.end());
    std::vector<float> tau(spec.head.tau.begin(), spec.head.tau.end());
    const std::vector<Eigen::Vector3f> g = vision::deformedVertices(m.mesh, sigma, tau);
    const Eigen::Matrix3f turn = (Eigen::AngleAxisf(spec.head.pitch, Eigen::Vector3f::UnitX()) *
                                  Eigen::AngleAxisf(spec.head.yaw, Eigen::Vector3f::UnitY()))
                                     .toRotationMatrix();
    const float c = std::cos(spec.head.roll), s = std::sin(spec.head.roll);
    std::vector<Eigen::Vector3f> placed;  // image x, y and depth towards the camera
    for (const Eigen::Vector3f& v : g) {
        const Eigen::Vector3f r = turn * v;
        const Eigen::Vector2f flipped(r.x(), -r.y());
        const Eigen::Vector2f image =
            Eigen::Vector2f(spec.head.translation.x, spec.head.translation.y) +
            spec.head.scale * Eigen::Vector2f(c * flipped.x() - s * flipped.y(),
                                              s * flipped.x() + c * flipped.y());
        placed.emplace_back(image.x(), image.y(), r.z());
        face.vertices.push_back({image.x(), image.y()});
    }

    drawFace(m, spec, placed, img);
    return face;
}

void drawFace(const vision::AamModel& m, const SyntheticFaceSpec& spec,
              const std::vector<Eigen::Vector3f>& placed, vision::ImageView img)
{
    const int width = img.width, height = img.height;
    const std::vector<float> grid = denseAppearance(m, spec.appearanceWeights);
    // The head around the face (forehead, temples, neck: the mesh stops at the brows and the
    // jaw line), an ellipse a little larger than the face in the tone of the face's border.
    float left = 1e9f, top = 1e9f, right = -1e9f, bottom = -1e9f;
    for (const Eigen::Vector3f& p : placed) {
        left = std::min(left, p.x()), right = std::max(right, p.x());
        top = std::min(top, p.y()), bottom = std::max(bottom, p.y());
    }
    const float cx = 0.5f * (left + right), cy = 0.5f * (top + bottom) - 0.1f * (bottom - top);
    const float rx = 0.62f * (right - left), ry = 0.75f * (bottom - top);
    const float skin = spec.gain * 0.6f + spec.bias;
    const auto lit = [&](int x, float grey) {
        const float u = std::clamp((static_cast<float>(x) - cx) / rx, -1.f, 1.f);
        return grey * (1.f - 0.5f * spec.lightFromRight * (1.f - u));
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float u = (static_cast<float>(x) - cx) / rx,
                        v = (static_cast<float>(y) - cy) / ry;
            if (u * u + v * v <= 1.f)
                img.row(y)[x] =
                    static_cast<std::uint8_t>(std::clamp(lit(x, skin - 20.f * v * v), 0.f, 255.f));
        }
    std::vector<float> depth(static_cast<std::size_t>(width) * height,
                             -std::numeric_limits<float>::infinity());
    for (const auto& tri : m.mesh.triangles) {
        const Eigen::Vector3f &a = placed[static_cast<std::size_t>(tri[0])],
                              &b = placed[static_cast<std::size_t>(tri[1])],
                              &cc = placed[static_cast<std::size_t>(tri[2])];
        Eigen::Matrix2f edges;
        edges << b.x() - a.x(), cc.x() - a.x(), b.y() - a.y(), cc.y() - a.y();
        if (std::abs(edges.determinant()) < 1e-6f)
            continue;
        const Eigen::Matrix2f inverse = edges.inverse();
        const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), cc.x()}))));
        const int x1 =
            std::min(width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), cc.x()}))));
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), cc.y()}))));
        const int y1 =
            std::min(height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), cc.y()}))));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const Eigen::Vector2f l = inverse * Eigen::Vector2f(static_cast<float>(x) - a.x(),
                                                                    static_cast<float>(y) - a.y());
                const float l0 = 1.f - l.x() - l.y();
                if (l0 < -1e-4f || l.x() < -1e-4f || l.y() < -1e-4f)
                    continue;
                const float z = l0 * a.z() + l.x() * b.z() + l.y() * cc.z();
                float& zb = depth[static_cast<std::size_t>(y) * width + x];
                if (z <= zb)
                    continue;
                zb = z;
                const auto s0 = [&](int k, int axis) {
                    return m
                        .meanShape[2 * static_cast<std::size_t>(tri[static_cast<std::size_t>(k)]) +
                                   static_cast<std::size_t>(axis)];
                };
                const float fx = l0 * s0(0, 0) + l.x() * s0(1, 0) + l.y() * s0(2, 0);
                const float fy = l0 * s0(0, 1) + l.x() * s0(1, 1) + l.y() * s0(2, 1);
                const float v =
                    lit(x, spec.gain * sampleBilinear(grid, m.frameWidth, m.frameHeight, fx, fy) +
                               spec.bias);
                img.row(y)[x] = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
            }
    }
}

float rmsDistance(const std::vector<vision::Point2f>& a, const vision::AamFitResult& fit)
{
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double dx = a[i].x - fit.vertices[i].x, dy = a[i].y - fit.vertices[i].y;
        sum += dx * dx + dy * dy;
    }
    return static_cast<float>(std::sqrt(sum / static_cast<double>(a.size())));
}

}  // namespace aam_test
