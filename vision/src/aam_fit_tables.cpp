// The AAM fit's tables, computed once from the model (§5; dissertation 5.3.2, eqs. 74-77, 85, and
// the speed work of 5.3.4).
//
// Where the text is silent:
//  - N's basis is taken about s0's centroid (the same span as eq. 76's, better conditioned), and
//    the shape modes are made orthogonal to it (Gram-Schmidt): the builder's Procrustes makes them
//    nearly so, and the composition's decomposition into q and p (Matthews & Baker) is exact only
//    when they are.
//  - The mean appearance's gradient is a central difference inside the model, one-sided at its
//    border (a pixel outside the model has no value to difference against).
//  - Each steepest-descent image is quantised to 12 bits (+-2047) with its own scale: the error
//    image takes 13 (1/16 grey level), so a product fits 24 bits and 128 of them an int32 (the dot
//    product's chunk, aam_kernels.hpp). The 2D Hessian is computed from the quantised images, so
//    it is exactly the one the gradient is formed with.
#include "aam_fit_tables.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vision::aam {

namespace {

[[noreturn]] void refuse(const std::string& what)
{
    throw std::invalid_argument("AAM fitter: " + what);
}

void checkSizes(const AamModel& m)
{
    const auto v = m.mesh.vertices.size();
    if (v < 3 || v > static_cast<std::size_t>(kAamMaxVertices))
        refuse(std::to_string(v) + " vertices (at most " + std::to_string(kAamMaxVertices) + ")");
    if (m.mesh.animationUnits.size() != kAamAnimationUnits ||
        m.mesh.shapeUnits.size() != kAamShapeUnits) {
        refuse("the mesh has " + std::to_string(m.mesh.animationUnits.size()) + " animation and " +
               std::to_string(m.mesh.shapeUnits.size()) + " shape units; the fit tracks 6 and 10");
    }
    if (m.shapeModeCount() > static_cast<std::size_t>(kAamMaxShapeModes))
        refuse(std::to_string(m.shapeModeCount()) + " shape modes (at most 24)");
    if (m.pixels.size() < 16 || m.meanShape.size() != 2 * v)
        refuse("the model has no appearance frame");
}

void similarityBasis(Tables& t)
{
    const int v = t.vertices;
    t.centre.setZero();
    for (int i = 0; i < v; ++i)
        t.centre += t.meanShape.segment<2>(2 * i);
    t.centre /= static_cast<float>(v);
    t.similarity.setZero(2 * v, 4);
    for (int i = 0; i < v; ++i) {
        const Eigen::Vector2f d = t.meanShape.segment<2>(2 * i) - t.centre;
        t.similarity.block<2, 4>(2 * i, 0) << d.x(), -d.y(), 1.f, 0.f, d.y(), d.x(), 0.f, 1.f;
    }
    t.similarityNorm = t.similarity.col(0).norm();
    t.similarity.leftCols(2) /= t.similarityNorm;
    t.similarity.rightCols(2) /= std::sqrt(static_cast<float>(v));
}

void orthogonalShapeModes(Tables& t, const AamModel& m)
{
    const int v = t.vertices;
    Eigen::MatrixXf modes(2 * v, static_cast<Eigen::Index>(m.shapeModeCount()));
    int kept = 0;
    for (std::size_t k = 0; k < m.shapeModeCount(); ++k) {
        Eigen::VectorXf s =
            Eigen::Map<const Eigen::VectorXf>(m.shapeModes.data() + k * 2 * v, 2 * v);
        s -= t.similarity * (t.similarity.transpose() * s);
        for (int j = 0; j < kept; ++j)
            s -= modes.col(j) * modes.col(j).dot(s);
        if (s.norm() < 0.1f)  // a mode that was mostly a similarity: nothing of its own left
            continue;
        modes.col(kept) = s.normalized();
        t.shapeLimits.push_back(3.f * std::sqrt(std::max(m.shapeVariances[k], 0.f)));
        ++kept;
    }
    t.shapeModes = modes.leftCols(kept);
    t.shapeModeCount = kept;
}

void frameTriangles(Tables& t, const AamModel& m)
{
    for (const auto& tri : m.mesh.triangles) {
        FrameTriangle f;
        f.v = tri;
        const Eigen::Vector2f a = t.meanShape.segment<2>(2 * tri[0]);
        Eigen::Matrix2f edges;
        edges.col(0) = t.meanShape.segment<2>(2 * tri[1]) - a;
        edges.col(1) = t.meanShape.segment<2>(2 * tri[2]) - a;
        if (std::abs(edges.determinant()) < 1e-6f)
            refuse("a triangle of the mean shape has no area");
        f.origin = a;
        f.inverseEdges = edges.inverse();
        t.frameTriangles.push_back(f);
    }
    // 5.3.4: the vertex -> triangles table, so a vertex's warp is averaged over its own triangles.
    std::vector<int> count(static_cast<std::size_t>(t.vertices) + 1, 0);
    for (const FrameTriangle& f : t.frameTriangles)
        for (int v : f.v)
            ++count[static_cast<std::size_t>(v) + 1];
    for (std::size_t v = 1; v < count.size(); ++v)
        count[v] += count[v - 1];
    t.vertexTriangleStart = count;
    t.vertexTriangles.assign(static_cast<std::size_t>(count.back()), 0);
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (std::size_t i = 0; i < t.frameTriangles.size(); ++i)
        for (int v : t.frameTriangles[i].v)
            t.vertexTriangles[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] =
                static_cast<int>(i);
    for (int v = 0; v < t.vertices; ++v) {
        if (count[static_cast<std::size_t>(v)] == count[static_cast<std::size_t>(v) + 1])
            refuse("vertex " + std::to_string(v) + " is in no triangle");
    }
}

/// The frame as a dense grid: each pixel's index in the model's table, or -1.
std::vector<int> modelIndexGrid(const AamModel& m)
{
    std::vector<int> grid(static_cast<std::size_t>(m.frameWidth) * m.frameHeight, -1);
    for (std::size_t i = 0; i < m.pixels.size(); ++i)
        grid[static_cast<std::size_t>(m.pixels[i].y) * m.frameWidth + m.pixels[i].x] =
            static_cast<int>(i);
    return grid;
}

/// Which model pixels the fit compares: those whose 8 neighbours are all model pixels. The outer
/// ring is left out because its image value mixes in what lies beyond the face (background, hair):
/// moving the outline changes it through edges A0's gradient cannot know (one-sided at the border),
/// so there the steepest-descent images disagree with the image's real change (measured: a shape
/// mode's image and the warped image's finite difference at cos 0.2-0.5 with the ring, 0.8-0.98
/// without; tests/vision/aam_fitter_test.cpp), and the Gauss-Newton steps were not descents.
std::vector<bool> fittedPixels(const AamModel& m, const std::vector<int>& grid)
{
    std::vector<bool> fitted(m.pixels.size(), true);
    auto model = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < m.frameWidth && y < m.frameHeight &&
               grid[static_cast<std::size_t>(y) * m.frameWidth + x] >= 0;
    };
    for (std::size_t i = 0; i < m.pixels.size(); ++i)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (!model(m.pixels[i].x + dx, m.pixels[i].y + dy))
                    fitted[i] = false;
    return fitted;
}

/// The row spans and the warp runs; `spanOfModel[i]` is model pixel i's span index.
void spansAndRuns(Tables& t, const AamModel& m, const std::vector<int>& grid,
                  std::vector<int>& spanOfModel)
{
    spanOfModel.assign(m.pixels.size(), 0);
    int offset = 0;
    for (int y = 0; y < m.frameHeight; ++y) {
        const int* row = grid.data() + static_cast<std::ptrdiff_t>(y) * m.frameWidth;
        int first = -1, last = -1;
        for (int x = 0; x < m.frameWidth; ++x) {
            if (row[x] >= 0) {
                first = first < 0 ? x : first;
                last = x;
            }
        }
        if (first < 0)
            continue;
        int triangle = m.pixels[static_cast<std::size_t>(row[first])].triangle;
        for (int x = first; x <= last; ++x) {
            const int index = row[x];
            if (index >= 0) {
                spanOfModel[static_cast<std::size_t>(index)] = offset + x - first;
                triangle = m.pixels[static_cast<std::size_t>(index)].triangle;
            }
            // A gap pixel extends the run before it: its value is masked out, its warp harmless.
            if (x == first || triangle != t.runs.back().triangle) {
                WarpRun run;
                run.y = static_cast<std::uint16_t>(y);
                run.x0 = static_cast<std::uint16_t>(x);
                run.triangle = static_cast<std::uint16_t>(triangle);
                run.offset = static_cast<std::uint32_t>(offset + x - first);
                t.runs.push_back(run);
            }
            ++t.runs.back().count;
        }
        offset += last - first + 1;
    }
    t.spanPixels = offset;
}

/// A0's gradient at model pixel (x, y) of the dense frame `a0` (NaN outside the model).
Eigen::Vector2f gradientAt(const std::vector<float>& a0, int width, int height, int x, int y)
{
    auto at = [&](int u, int v) {
        if (u < 0 || v < 0 || u >= width || v >= height)
            return std::nanf("");
        return a0[static_cast<std::size_t>(v) * width + u];
    };
    auto difference = [](float minus, float centre, float plus) {
        if (!std::isnan(minus) && !std::isnan(plus))
            return 0.5f * (plus - minus);
        if (!std::isnan(plus))
            return plus - centre;
        if (!std::isnan(minus))
            return centre - minus;
        return 0.f;
    };
    const float c = at(x, y);
    return {difference(at(x - 1, y), c, at(x + 1, y)), difference(at(x, y - 1), c, at(x, y + 1))};
}

/// The appearance modes with the mean appearance's direction taken out, orthonormal again. The
/// builder's modes hold some of it (the training images' contrast, matched to the mean by least
/// squares, varies along A0); the fit's gain carries that direction, and a mode that also carried
/// it would make the gain unobservable: projected out of the error, it would leave the fit free to
/// raise the gain and shrink the residual with it.
Eigen::MatrixXf modesOrthogonalToMean(const AamModel& m, const std::vector<bool>& fitted,
                                      std::vector<float>& keptStd)
{
    keptStd.clear();
    const auto pixels = static_cast<Eigen::Index>(m.pixels.size());
    Eigen::VectorXf mean = Eigen::Map<const Eigen::VectorXf>(m.meanAppearance.data(), pixels);
    Eigen::MatrixXf modes = Eigen::Map<const Eigen::MatrixXf>(
        m.appearanceModes.data(), pixels, static_cast<Eigen::Index>(m.appearanceModeCount()));
    for (Eigen::Index i = 0; i < pixels; ++i) {  // over the fitted pixels only
        if (!fitted[static_cast<std::size_t>(i)]) {
            mean(i) = 0.f;
            modes.row(i).setZero();
        }
    }
    const Eigen::VectorXf unitMean = mean.normalized();
    const Eigen::MatrixXf original = modes;
    Eigen::Index kept = 0;
    for (Eigen::Index k = 0; k < modes.cols(); ++k) {
        Eigen::VectorXf a = modes.col(k);
        a -= unitMean * unitMean.dot(a);
        for (Eigen::Index j = 0; j < kept; ++j)
            a -= modes.col(j) * modes.col(j).dot(a);
        if (a.norm() < 0.1f)
            continue;
        modes.col(kept++) = a.normalized();
    }
    // Each kept direction's standard deviation over the training faces: the model's variances
    // projected on it (the builder's first mode is mostly the mean's direction, so its own
    // variance would overstate what is left of it).
    for (Eigen::Index k = 0; k < kept; ++k) {
        double variance = 0;
        for (Eigen::Index j = 0; j < original.cols(); ++j) {
            const double along = modes.col(k).dot(original.col(j));
            variance += m.appearanceVariances[static_cast<std::size_t>(j)] * along * along;
        }
        keptStd.push_back(static_cast<float>(std::sqrt(std::max(variance, 1e-12))));
    }
    return modes.leftCols(kept);
}

Quantised quantise(const Eigen::VectorXf& image, int largest)
{
    Quantised q;
    const float peak = image.cwiseAbs().maxCoeff();
    q.scale = peak > 0.f ? static_cast<float>(largest) / peak : 1.f;
    q.values.resize(static_cast<std::size_t>(image.size()));
    for (Eigen::Index i = 0; i < image.size(); ++i)
        q.values[static_cast<std::size_t>(i)] =
            static_cast<std::int16_t>(std::lround(image(i) * q.scale));
    return q;
}

/// Eqs. 74 and 85: the steepest-descent images over the spans, projected out of span(A_i).
void steepestDescent(Tables& t, const AamModel& m, const std::vector<int>& spanOfModel,
                     const std::vector<bool>& fitted)
{
    std::vector<float> dense(static_cast<std::size_t>(m.frameWidth) * m.frameHeight, std::nanf(""));
    for (std::size_t i = 0; i < m.pixels.size(); ++i)
        dense[static_cast<std::size_t>(m.pixels[i].y) * m.frameWidth + m.pixels[i].x] =
            m.meanAppearance[i];
    const int count = 6 + t.shapeModeCount;
    const auto pixels = static_cast<Eigen::Index>(m.pixels.size());
    Eigen::MatrixXf sd = Eigen::MatrixXf::Zero(pixels, count);
    for (Eigen::Index i = 0; i < pixels; ++i) {
        const AppearancePixel& px = m.pixels[static_cast<std::size_t>(i)];
        const Eigen::Vector2f grad = gradientAt(dense, m.frameWidth, m.frameHeight, px.x, px.y);
        const FrameTriangle& f = t.frameTriangles[px.triangle];
        const Eigen::Vector2f l = f.inverseEdges * (Eigen::Vector2f(px.x, px.y) - f.origin);
        const float bary[3] = {1.f - l.x() - l.y(), l.x(), l.y()};
        sd(i, 0) = m.meanAppearance[static_cast<std::size_t>(i)];  // alpha: contrast
        sd(i, 1) = 1.f;                                            // beta: brightness
        sd.block<1, 4>(i, 2) = grad.transpose() * similarityAt(t, px.x, px.y);
        for (int j = 0; j < t.shapeModeCount; ++j) {
            Eigen::Vector2f dw = Eigen::Vector2f::Zero();
            for (int k = 0; k < 3; ++k)
                dw +=
                    bary[k] * t.shapeModes.col(j).segment<2>(2 * f.v[static_cast<std::size_t>(k)]);
            sd(i, 6 + j) = grad.dot(dw);
        }
        if (!fitted[static_cast<std::size_t>(i)])
            sd.row(i).setZero();
    }
    // Eq. 74: the appearance modes projected out.
    const Eigen::MatrixXf modes = modesOrthogonalToMean(m, fitted, t.appearanceModeStd);
    sd -= modes * (modes.transpose() * sd);
    for (int j = 0; j < count; ++j) {
        Eigen::VectorXf span = Eigen::VectorXf::Zero(t.spanPixels);
        for (Eigen::Index i = 0; i < pixels; ++i)
            span(spanOfModel[static_cast<std::size_t>(i)]) = sd(i, j);
        t.steepest.push_back(quantise(span, kSteepestMax));
    }
    for (Eigen::Index k = 0; k < modes.cols(); ++k) {
        Eigen::VectorXf span = Eigen::VectorXf::Zero(t.spanPixels);
        for (Eigen::Index i = 0; i < pixels; ++i)
            span(spanOfModel[static_cast<std::size_t>(i)]) = modes(i, k);
        t.appearanceModes.push_back(quantise(span, kSteepestMax));
    }
    t.hessian2d.resize(count, count);
    for (int a = 0; a < count; ++a) {
        for (int b = a; b < count; ++b) {
            std::int64_t sum = 0;
            for (int i = 0; i < t.spanPixels; ++i)
                sum += std::int64_t{t.steepest[static_cast<std::size_t>(a)]
                                        .values[static_cast<std::size_t>(i)]} *
                       t.steepest[static_cast<std::size_t>(b)].values[static_cast<std::size_t>(i)];
            t.hessian2d(a, b) = t.hessian2d(b, a) =
                static_cast<double>(sum) /
                (static_cast<double>(t.steepest[static_cast<std::size_t>(a)].scale) *
                 t.steepest[static_cast<std::size_t>(b)].scale);
        }
    }
}

void appearanceAndMask(Tables& t, const AamModel& m, const std::vector<int>& spanOfModel,
                       const std::vector<bool>& fitted)
{
    t.modelPixels = 0;
    t.mask.assign(static_cast<std::size_t>(t.spanPixels), 0);
    t.meanAppearance.assign(static_cast<std::size_t>(t.spanPixels), 0);
    for (std::size_t i = 0; i < m.pixels.size(); ++i) {
        const auto s = static_cast<std::size_t>(spanOfModel[i]);
        t.mask[s] = fitted[i] ? -1 : 0;
        t.modelPixels += fitted[i] ? 1 : 0;
        t.meanAppearance[s] = static_cast<std::int16_t>(
            std::clamp(std::lround(m.meanAppearance[i] * kAppearanceOne), -32767L, 32767L));
    }
}

void headTables(Tables& t, const AamModel& m)
{
    t.headVertices = m.mesh.vertices;
    t.headUnits.assign(m.mesh.vertices.size(),
                       Eigen::Matrix<float, 3, kAamShapeUnits + kAamAnimationUnits>::Zero());
    auto add = [&](const std::vector<CandideUnit>& units, int firstColumn) {
        for (std::size_t u = 0; u < units.size(); ++u)
            for (std::size_t k = 0; k < units[u].vertices.size(); ++k)
                t.headUnits[static_cast<std::size_t>(units[u].vertices[k])].col(
                    firstColumn + static_cast<int>(u)) += units[u].displacements[k];
    };
    add(m.mesh.shapeUnits, 0);
    add(m.mesh.animationUnits, kAamShapeUnits);
}

}  // namespace

Eigen::Matrix<float, 2, 4> similarityAt(const Tables& t, float x, float y)
{
    const float dx = (x - t.centre.x()) / t.similarityNorm,
                dy = (y - t.centre.y()) / t.similarityNorm;
    const float unit = 1.f / std::sqrt(static_cast<float>(t.vertices));
    Eigen::Matrix<float, 2, 4> b;
    b << dx, -dy, unit, 0.f, dy, dx, 0.f, unit;
    return b;
}

Tables buildTables(const AamModel& model)
{
    checkSizes(model);
    Tables t;
    t.vertices = static_cast<int>(model.mesh.vertices.size());
    t.triangles = static_cast<int>(model.mesh.triangles.size());
    t.appearanceModeCount = static_cast<int>(model.appearanceModeCount());
    t.meanShape = Eigen::Map<const Eigen::VectorXf>(model.meanShape.data(), 2 * t.vertices);
    Eigen::Vector2f low(1e9f, 1e9f), high(-1e9f, -1e9f);
    for (int i = 0; i < t.vertices; ++i) {
        low = low.cwiseMin(t.meanShape.segment<2>(2 * i));
        high = high.cwiseMax(t.meanShape.segment<2>(2 * i));
    }
    t.boxLow = low;
    t.boxSize = high - low;
    similarityBasis(t);
    orthogonalShapeModes(t, model);
    frameTriangles(t, model);
    const std::vector<int> grid = modelIndexGrid(model);
    std::vector<int> spanOfModel;
    spansAndRuns(t, model, grid, spanOfModel);
    const std::vector<bool> fitted = fittedPixels(model, grid);
    appearanceAndMask(t, model, spanOfModel, fitted);
    steepestDescent(t, model, spanOfModel, fitted);
    headTables(t, model);
    return t;
}

}  // namespace vision::aam
