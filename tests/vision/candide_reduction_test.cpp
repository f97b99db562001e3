// The dissertation's cut of CANDIDE (§5) on a small hand-made mesh: vertices above the eyebrows and
// their triangles dropped, unused vertices dropped, kept units renumbered, a missing unit named.
#include "vision/candide_reduction.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

/// 113 vertices numbered as CANDIDE-3's, at y = 0 but for vertex 0 above the brows (15-18,
/// 48-51); a triangle through 0, three below, one through an iris vertex (70); the other vertices
/// used by none but those of the eye openings; all the kept units, a vertex or two each.
vision::CandideMesh toyMesh()
{
    vision::CandideMesh m;
    for (int i = 0; i < 113; ++i) {
        m.vertices.emplace_back(static_cast<float>(i), 0.f, 0.f);
        m.candideNumber.push_back(i);
    }
    m.vertices[0].y() = 1.f;
    m.vertices[16].y() = 0.5f;  // the brow's top: 0 is still above it
    m.triangles = {{0, 15, 16}, {15, 16, 17}, {17, 18, 48}, {49, 50, 51}, {49, 70, 51}};
    for (const auto& kept : vision::kTrackedAnimationUnits) {
        m.animationUnits.push_back({std::string(kept.name) + " (AU)",
                                    std::string(kept.label),
                                    {0, 17},
                                    {{0, 1, 0}, {0, 2, 0}}});
    }
    m.animationUnits.push_back({"Eyes closed (AU42)", "AUV6", {15}, {{0, 1, 0}}});
    for (auto name : vision::kTrackedShapeUnits)
        m.shapeUnits.push_back({std::string(name), "", {18}, {{1, 0, 0}}});
    for (auto name : vision::kDroppedShapeUnits)
        m.shapeUnits.push_back({std::string(name), "", {0}, {{0, 1, 0}}});
    return m;
}

TEST(CandideReduction, DropsWhatIsAboveTheBrowsAndUnused)
{
    const vision::CandideMesh face = vision::reduceCandideForTracking(toyMesh());
    EXPECT_EQ(face.candideNumber,
              (std::vector<int>{15, 16, 17, 18, 20, 21, 22, 23,  48,  49,  50,  51,
                                53, 54, 55, 56, 97, 98, 99, 100, 105, 106, 107, 108}));
    ASSERT_EQ(face.triangles.size(), 3u + 12u);
    EXPECT_EQ(face.triangles[0], (std::array<int, 3>{0, 1, 2}));
    EXPECT_EQ(face.indexOfCandideVertex(48), 8);
    EXPECT_EQ(face.indexOfCandideVertex(0), -1);
    EXPECT_EQ(face.indexOfCandideVertex(70), -1);
    // The left eye's strip: outer corner 20 with the lids' outer edges 97 and 99 first.
    EXPECT_EQ(face.triangles[3], (std::array<int, 3>{4, 16, 18}));
}

TEST(CandideReduction, KeepsTheSixAnimationAndTenShapeUnitsInOrder)
{
    const vision::CandideMesh face = vision::reduceCandideForTracking(toyMesh());
    ASSERT_EQ(face.animationUnits.size(), 6u);
    EXPECT_EQ(face.animationUnits[0].label, "AUV11");
    EXPECT_EQ(face.animationUnits[5].label, "AUV14");
    // Vertex 0 is gone, so each unit keeps only its entry on 17 (now index 2).
    EXPECT_EQ(face.animationUnits[0].vertices, (std::vector<int>{2}));
    EXPECT_FLOAT_EQ(face.animationUnits[0].displacements[0].y(), 2.f);
    ASSERT_EQ(face.shapeUnits.size(), 10u);
    EXPECT_EQ(face.shapeUnits[0].name, "Eyebrows vertical position");
    EXPECT_EQ(face.shapeUnits[9].name, "Chin width");
}

TEST(CandideReduction, AMissingUnitIsNamed)
{
    vision::CandideMesh m = toyMesh();
    m.animationUnits.erase(m.animationUnits.begin() + 3);  // Outer brow raiser
    try {
        vision::reduceCandideForTracking(m);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "CANDIDE mesh: no animation unit AUV5 (Outer brow raiser)");
    }
}

TEST(CandideMesh, DeformsLinearly)
{
    const vision::CandideMesh face = vision::reduceCandideForTracking(toyMesh());
    std::vector<float> sigma(10, 0.f), tau(6, 0.f);
    sigma[0] = 2.f;  // +2 x on vertex 18 (index 3)
    tau[1] = 0.5f;   // +1 y on vertex 17 (index 2)
    const auto g = vision::deformedVertices(face, sigma, tau);
    EXPECT_FLOAT_EQ(g[3].x(), 20.f);
    EXPECT_FLOAT_EQ(g[2].y(), 1.f);
    EXPECT_THROW(vision::deformedVertices(face, {}, tau), std::invalid_argument);
}

}  // namespace
