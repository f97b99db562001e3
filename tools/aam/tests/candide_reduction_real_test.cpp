// The dissertation's cut applied to the real CANDIDE-3 (§5): exactly which vertices go, the
// triangles left tile the face without overlap in the frontal view (the piecewise affine warp
// needs that), the kept units act on kept vertices.
#include "test_paths.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace {

const std::string kCandide = testing_support::sharedData("candide3/candide3.wfm");

/// Twice the signed area of triangle (p, q, r) in the frontal (x, y) view.
float cross(const Eigen::Vector3f& p, const Eigen::Vector3f& q, const Eigen::Vector3f& r)
{
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
}

class RealCandide : public ::testing::Test {
protected:
    void SetUp() override
    {
        if (!std::filesystem::exists(kCandide))
            GTEST_SKIP() << kCandide << " not present";
        full = aam::loadWfm(kCandide);
        face = vision::reduceCandideForTracking(full);
    }
    vision::CandideMesh full, face;
};

TEST_F(RealCandide, DropsTheTopOfTheHeadAndTheUnusedDuplicates)
{
    std::vector<int> dropped;
    for (int v = 0; v < 113; ++v) {
        if (face.indexOfCandideVertex(v) < 0)
            dropped.push_back(v);
    }
    // Above the brows: top of skull, forehead, hair line, sides of skull (Ahlberg's appendix A);
    // unused: 4 and the "not used (identical to ...)" 35-39, 41-43; the iris box 67-74 with the
    // eyeball surfaces.
    EXPECT_EQ(dropped, (std::vector<int>{0,  1,  2,  4,  11, 12, 13, 14, 34, 35, 36, 37, 38, 39, 41,
                                         42, 43, 44, 45, 46, 47, 67, 68, 69, 70, 71, 72, 73, 74}));
    EXPECT_EQ(face.vertices.size(), 84u);
    EXPECT_EQ(face.triangles.size(), 160u - 28u + 12u);  // 28 eyeball surfaces, 6 per eye opening
}

TEST_F(RealCandide, KeepsTheDissertationsUnits)
{
    ASSERT_EQ(face.animationUnits.size(), 6u);
    const char* names[] = {"Jaw drop (AU26/27)",      "Lip stretcher (AU20)",
                           "Brow lowerer (AU4)",      "Outer brow raiser (AU2)",
                           "Upper lip raiser (AU10)", "Lip corner depressor (AU13/15)"};
    for (std::size_t i = 0; i < 6; ++i)
        EXPECT_EQ(face.animationUnits[i].name, names[i]);
    ASSERT_EQ(face.shapeUnits.size(), 10u);
    for (const auto& unit : face.shapeUnits) {
        // A kept unit loses only its entries on dropped vertices (the unused 4, the iris box).
        const vision::CandideUnit* original = vision::findUnit(full.shapeUnits, unit.name);
        ASSERT_NE(original, nullptr);
        std::size_t onKept = 0;
        for (int v : original->vertices)
            onKept += face.indexOfCandideVertex(v) >= 0 ? 1 : 0;
        EXPECT_EQ(unit.vertices.size(), onKept) << unit.name;
        EXPECT_GE(onKept + 8, original->vertices.size()) << unit.name;
    }
}

TEST_F(RealCandide, TheEyeOpeningsAreCovered)
{
    // The centres of both eyes lie in exactly one triangle (the test below: in at most one).
    for (const Eigen::Vector3f& p :
         {Eigen::Vector3f(0.3f, 0.17f, 0), Eigen::Vector3f(-0.3f, 0.17f, 0)}) {
        int covering = 0;
        for (const auto& t : face.triangles) {
            const auto& a = face.vertices[static_cast<std::size_t>(t[0])];
            const auto& b = face.vertices[static_cast<std::size_t>(t[1])];
            const auto& c = face.vertices[static_cast<std::size_t>(t[2])];
            const float s = cross(a, b, c) > 0 ? 1.f : -1.f;
            if (s * cross(a, b, p) > 0 && s * cross(b, c, p) > 0 && s * cross(c, a, p) > 0)
                ++covering;
        }
        EXPECT_EQ(covering, 1);
    }
}

TEST_F(RealCandide, TrianglesDoNotOverlapInTheFrontalView)
{
    // Count, on a fine grid, the triangles covering each point; strictly inside means no edges.
    int overlaps = 0;
    for (float x = -0.7f; x <= 0.7f; x += 0.005f) {
        for (float y = -0.9f; y <= 0.4f; y += 0.005f) {
            const Eigen::Vector3f p(x, y, 0);
            int covering = 0;
            for (const auto& t : face.triangles) {
                const auto& a = face.vertices[static_cast<std::size_t>(t[0])];
                const auto& b = face.vertices[static_cast<std::size_t>(t[1])];
                const auto& c = face.vertices[static_cast<std::size_t>(t[2])];
                const float s = cross(a, b, c) > 0 ? 1.f : -1.f;
                if (s * cross(a, b, p) > 1e-6f && s * cross(b, c, p) > 1e-6f &&
                    s * cross(c, a, p) > 1e-6f)
                    ++covering;
            }
            if (covering > 1)
                ++overlaps;
        }
    }
    EXPECT_EQ(overlaps, 0);
}

}  // namespace
