// TrackedFaceFitter (§5.3): the AAM fit per tracked face on synthetic renders (the model's own
// appearance on the posed CANDIDE head, tests/vision/aam_synthetic_face.*), given the face box a
// tracker would give (the true mesh's box widened back by AamBoxPlacement). A new track starts
// from its box and a held one follows it; a fit that fails verification or leaves the box is not
// ok (the 2D pose) and starts again from the box next frame; only shown faces are fitted; a track
// that is gone frees its slot. Skips without the demo model (scripts/dev model).
#include "vision/tracked_face_fitter.hpp"

#include "aam_demo_model.hpp"
#include "aam_synthetic_face.hpp"
#include "alloc_counter.hpp"
#include "test_paths.hpp"
#include "vision/aam_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

namespace {

using aam_test::SyntheticFace;
using aam_test::SyntheticFaceSpec;

constexpr float kRadians = 3.14159265f / 180.f;
constexpr int kWidth = 320, kHeight = 240;

using aam_test::demoModel;

SyntheticFace posedFace(float yawDeg, float pitchDeg, float rollDeg, float shiftX = 0.f)
{
    const vision::AamModel& m = *demoModel();
    static const vision::AamHead mean = aam_test::meanShapeHead(m);
    SyntheticFaceSpec spec;
    spec.head = mean;
    spec.head.scale = 120.f / aam_test::meshWidthUnits(m);
    spec.head.yaw = yawDeg * kRadians;
    spec.head.pitch = pitchDeg * kRadians;
    spec.head.roll = rollDeg * kRadians;
    spec.head.translation = {kWidth * 0.5f + shiftX, kHeight * 0.5f};
    spec.appearanceWeights = {0.4f, -0.3f, 0.2f};
    spec.backgroundSeed = 7;
    return aam_test::renderSyntheticFace(m, spec, kWidth, kHeight);
}

/// The tracker's box for a face whose mesh box is `mesh`: the placement undone.
vision::TrackedFace trackedFace(int id, const vision::AamStart& mesh,
                                const vision::AamBoxPlacement& placement)
{
    vision::TrackedFace f;
    f.id = id;
    f.size = mesh.width / placement.widthOverBox;
    const float roll = mesh.rollDegrees * kRadians;
    const float down = placement.downOverBox * f.size;
    f.centre = {mesh.centre.x + down * std::sin(roll), mesh.centre.y - down * std::cos(roll)};
    f.rollDegrees = mesh.rollDegrees;
    f.state = vision::FaceState::Confirmed;
    return f;
}

TEST(TrackedFaceFitter, StartForPutsTheMeshBoxWhereThePlacementSays)
{
    REQUIRE_DEMO_MODEL();
    vision::TrackedFaceFitter fitter(*demoModel());
    const vision::AamStart mesh{{150.f, 130.f}, 100.f, 12.f};
    const vision::TrackedFace f = trackedFace(1, mesh, fitter.options().placement);
    const vision::AamStart s = fitter.startFor(f);
    EXPECT_NEAR(s.centre.x, 150.f, 1e-3f);
    EXPECT_NEAR(s.centre.y, 130.f, 1e-3f);
    EXPECT_NEAR(s.width, 100.f, 1e-3f);
    EXPECT_FLOAT_EQ(s.rollDegrees, 12.f);
}

TEST(TrackedFaceFitter, NewTrackStartsFromItsBoxThenFollowsWithTheFullPose)
{
    REQUIRE_DEMO_MODEL();
    vision::TrackedFaceFitter fitter(*demoModel());
    const float yaws[] = {10.f, 14.f, 18.f, 22.f};
    for (int frame = 0; frame < 4; ++frame) {
        const SyntheticFace face = posedFace(yaws[frame], -5.f, 4.f, 2.f * frame);
        const vision::TrackedFace tracked =
            trackedFace(3, face.box(4.f), fitter.options().placement);
        fitter.process(face.image.view(), {&tracked, 1});
        ASSERT_EQ(fitter.fits().size(), 1u);
        const vision::FaceFit& fit = fitter.fits()[0];
        SCOPED_TRACE(frame);
        EXPECT_EQ(fit.faceId, 3);
        EXPECT_TRUE(fit.fitted);
        EXPECT_EQ(fit.started, frame == 0) << "a held track follows, a new one starts";
        ASSERT_TRUE(fit.ok()) << fit.status() << " error " << fit.fitError;
        EXPECT_NEAR(fit.yawDegrees, yaws[frame], 4.f);
        EXPECT_NEAR(fit.pitchDegrees, -5.f, 4.f);
        EXPECT_NEAR(fit.rollDegrees, 4.f, 1.5f);
        EXPECT_GT(fit.iterations, 0);
        EXPECT_EQ(fit.vertexCount, fitter.vertexCount());
        // The eyes between the fitted eye corners, the size that of the tracker's box.
        EXPECT_NEAR(fit.faceSize, tracked.size, 0.15f * tracked.size);
        EXPECT_LT(fit.eyeMidpoint.y, tracked.centre.y);
        EXPECT_NEAR(fit.eyeMidpoint.x, tracked.centre.x, 0.15f * tracked.size);
    }
}

TEST(TrackedFaceFitter, AFitThatLeavesTheBoxFallsBackAndStartsAgainFromTheBox)
{
    REQUIRE_DEMO_MODEL();
    vision::TrackedFaceFitterOptions options;
    options.maxCentreShift = 0.f;  // no fitted mesh sits exactly on its start: every fit fails
    vision::TrackedFaceFitter fitter(*demoModel(), options);
    const SyntheticFace face = posedFace(0.f, 0.f, 0.f);
    const vision::TrackedFace tracked = trackedFace(5, face.box(0.f), options.placement);
    for (int frame = 0; frame < 3; ++frame) {
        fitter.process(face.image.view(), {&tracked, 1});
        const vision::FaceFit& fit = fitter.fits()[0];
        EXPECT_TRUE(fit.fitted);
        EXPECT_FALSE(fit.plausible);
        EXPECT_FALSE(fit.ok());
        EXPECT_STREQ(fit.status(), "implausible");
        EXPECT_TRUE(fit.started) << "frame " << frame << ": a failed fit is not followed";
    }
}

TEST(TrackedFaceFitter, NoFaceWhereTheBoxIsIsNotShown)
{
    REQUIRE_DEMO_MODEL();
    vision::TrackedFaceFitter fitter(*demoModel());
    // The face far to the right, the box on the background at the left.
    const SyntheticFace face = posedFace(0.f, 0.f, 0.f, 100.f);
    vision::AamStart empty = face.box(0.f);
    empty.centre.x -= 200.f;
    const vision::TrackedFace tracked = trackedFace(2, empty, fitter.options().placement);
    for (int frame = 0; frame < 2; ++frame) {
        fitter.process(face.image.view(), {&tracked, 1});
        const vision::FaceFit& fit = fitter.fits()[0];
        EXPECT_FALSE(fit.ok()) << fit.status() << " error " << fit.fitError << " yaw "
                               << fit.yawDegrees;
        EXPECT_TRUE(fit.started);
    }
}

TEST(TrackedFaceFitter, OnlyShownFacesAreFittedAndGoneTracksFreeTheirSlots)
{
    REQUIRE_DEMO_MODEL();
    vision::TrackedFaceFitter fitter(*demoModel());
    const SyntheticFace face = posedFace(0.f, 0.f, 0.f);
    vision::TrackedFace faces[2] = {trackedFace(1, face.box(0.f), fitter.options().placement),
                                    trackedFace(2, face.box(0.f), fitter.options().placement)};
    faces[1].state = vision::FaceState::Tentative;
    fitter.process(face.image.view(), faces);
    ASSERT_EQ(fitter.fits().size(), 2u);
    EXPECT_TRUE(fitter.fits()[0].fitted);
    EXPECT_FALSE(fitter.fits()[1].fitted);
    EXPECT_EQ(fitter.fits()[1].faceId, 2);
    EXPECT_STREQ(fitter.fits()[1].status(), "not-fitted");
    // More tracks over time than slots: the gone ones make room.
    for (int id = 10; id < 10 + 3 * vision::TrackedFaceFitter::kMaxFaces; ++id) {
        vision::TrackedFace f = faces[0];
        f.id = id;
        fitter.process(face.image.view(), {&f, 1});
        ASSERT_EQ(fitter.fits().size(), 1u);
        EXPECT_TRUE(fitter.fits()[0].fitted) << id;
        EXPECT_TRUE(fitter.fits()[0].started) << id;
    }
}

}  // namespace

TEST(TrackedFaceFitter, ASignatureSettlesAfterItsFitsAndEnrolmentCanAskForMore)
{
    REQUIRE_DEMO_MODEL();
    vision::TrackedFaceFitterOptions options;
    options.signatureFits = 3;
    vision::TrackedFaceFitter fitter(*demoModel(), options);
    const SyntheticFace face = posedFace(5.f, 0.f, 0.f, 0.f);
    const vision::TrackedFace tracked = trackedFace(7, face.box(4.f), fitter.options().placement);
    int settledAt = -1;
    for (int frame = 0; frame < 12 && settledAt < 0; ++frame) {
        fitter.process(face.image.view(), {&tracked, 1});
        const vision::FaceFit& fit = fitter.fits()[0];
        ASSERT_TRUE(fit.ok()) << fit.status();
        if (fit.signatureSettled)
            settledAt = frame;
    }
    ASSERT_GE(settledAt, 0) << "the signature never settled";
    EXPECT_EQ(fitter.fits()[0].signature.samples, 3);
    const vision::FaceSignature& settled = fitter.fits()[0].signature;
    EXPECT_GT(settled.appearanceCount, 0) << "the appearance parameters are in the signature";
    float magnitude = 0.f;
    for (int i = 0; i < settled.appearanceCount; ++i)
        magnitude += std::abs(settled.appearance[static_cast<std::size_t>(i)]);
    EXPECT_GT(magnitude, 0.f);
    ASSERT_EQ(settled.textureCount, fitter.options().fit.textureGrid *
                                        fitter.options().fit.textureGrid * vision::kAamLbpBins)
        << "the texture descriptor is in the signature";
    // Each cell's values (255 * sqrt of its patterns' shares) are about a unit vector.
    for (int cell = 0; cell * vision::kAamLbpBins < settled.textureCount; ++cell) {
        float squares = 0.f;
        for (int b = 0; b < vision::kAamLbpBins; ++b) {
            const float v =
                settled.texture[static_cast<std::size_t>(cell * vision::kAamLbpBins + b)];
            squares += v * v / (255.f * 255.f);
        }
        EXPECT_NEAR(squares, 1.f, 0.1f) << "cell " << cell;
    }
    fitter.process(face.image.view(), {&tracked, 1});
    EXPECT_EQ(fitter.fits()[0].signature.samples, 3) << "a settled signature no longer changes";

    EXPECT_FALSE(fitter.collectSignature(99, 2)) << "no such track";
    ASSERT_TRUE(fitter.collectSignature(7, 2));
    fitter.process(face.image.view(), {&tracked, 1});
    EXPECT_FALSE(fitter.fits()[0].signatureSettled);
    fitter.process(face.image.view(), {&tracked, 1});
    EXPECT_TRUE(fitter.fits()[0].signatureSettled);
    EXPECT_EQ(fitter.fits()[0].signature.samples, 5);
}

TEST(TrackedFaceFitter, CollectingASignatureAllocatesNothing)
{
    REQUIRE_DEMO_MODEL();
    if (!testing_support::allocationCountingAvailable())
        GTEST_SKIP() << "allocation counting is not available in this build";
    vision::TrackedFaceFitterOptions options;
    options.signatureFits = 20;
    vision::TrackedFaceFitter fitter(*demoModel(), options);
    const SyntheticFace face = posedFace(5.f, 0.f, 0.f, 0.f);
    const vision::TrackedFace tracked = trackedFace(3, face.box(4.f), fitter.options().placement);
    testing_support::AllocationScope scope;
    for (int frame = 0; frame < 8; ++frame)
        fitter.process(face.image.view(), {&tracked, 1});
    EXPECT_EQ(scope.counts().cxxNew, 0);
    EXPECT_EQ(scope.counts().ownMalloc, 0);
    EXPECT_GT(fitter.fits()[0].signature.samples, 0) << "the signature was collecting";
    EXPECT_FALSE(fitter.fits()[0].signatureSettled);
}

// For the signature only: fits the fitter rejects for a residual above its maxResidual (here set
// below any fit's) but within signatureMaxResidual still make a signature, while none is shown;
// without it (0) they make none. The default takes residuals up to 1.0.
TEST(TrackedFaceFitter, FitsRejectedOnlyForTheirResidualCanStillMakeASignature)
{
    REQUIRE_DEMO_MODEL();
    EXPECT_EQ(vision::TrackedFaceFitterOptions{}.signatureMaxResidual, 1.f);
    const SyntheticFace face = posedFace(5.f, 0.f, 0.f, 0.f);
    for (const float signatureResidual : {0.f, 50.f}) {
        vision::TrackedFaceFitterOptions options;
        options.signatureFits = 3;
        options.fit.maxResidual = 1e-4f;  // every fit rejected for its residual
        options.signatureMaxResidual = signatureResidual;
        vision::TrackedFaceFitter fitter(*demoModel(), options);
        const vision::TrackedFace tracked =
            trackedFace(4, face.box(4.f), fitter.options().placement);
        for (int frame = 0; frame < 12; ++frame) {
            fitter.process(face.image.view(), {&tracked, 1});
            const vision::FaceFit& fit = fitter.fits()[0];
            ASSERT_FALSE(fit.ok()) << "frame " << frame << ": never shown";
            ASSERT_EQ(fit.outcome, vision::AamFitOutcome::Rejected) << "frame " << frame;
        }
        const vision::FaceFit& last = fitter.fits()[0];
        if (signatureResidual > 0.f) {
            EXPECT_TRUE(last.signatureSettled);
            EXPECT_EQ(last.signature.samples, 3);
            EXPECT_GT(last.signature.textureCount, 0);
        } else {
            EXPECT_EQ(last.signature.samples, 0) << "only ok fits";
            EXPECT_FALSE(last.signatureSettled);
        }
    }
}

/// §5.3.3 carries a fit from frame to frame; a carried fit whose residual rose (here: a dark hand
/// over the mouth and chin) is fitted again from the tracker's box in the same frame, and the
/// better of the two kept; a follow that holds is not fitted again.
TEST(TrackedFaceFitter, AFollowWhoseResidualRoseIsFittedAgainFromItsBox)
{
    REQUIRE_DEMO_MODEL();
    EXPECT_GT(vision::TrackedFaceFitterOptions{}.restartResidualRise, 0.f);
    const SyntheticFace face = posedFace(5.f, 0.f, 0.f, 0.f);
    SyntheticFace covered = posedFace(5.f, 0.f, 0.f, 0.f);
    const vision::AamStart mesh = face.box(0.f);
    vision::ImageView hand = covered.image.view();
    const int x0 = static_cast<int>(mesh.centre.x - 0.5f * mesh.width);
    for (int y = static_cast<int>(mesh.centre.y + 0.1f * mesh.width); y < hand.height; ++y)
        for (int x = std::max(x0, 0); x < std::min(x0 + static_cast<int>(mesh.width), hand.width);
             ++x)
            hand.row(y)[x] = 30;

    vision::TrackedFaceFitterOptions never;
    never.restartResidualRise = 0.f;
    vision::TrackedFaceFitter plain(*demoModel(), never), restarting(*demoModel());
    const vision::TrackedFace tracked = trackedFace(6, mesh, never.placement);
    for (int frame = 0; frame < 4; ++frame) {
        const vision::ConstImageView image = frame < 3 ? face.image.view() : covered.image.view();
        plain.process(image, {&tracked, 1});
        restarting.process(image, {&tracked, 1});
        const vision::FaceFit& a = plain.fits()[0];
        const vision::FaceFit& b = restarting.fits()[0];
        SCOPED_TRACE(frame);
        if (frame < 3) {
            ASSERT_TRUE(a.ok() && b.ok());
            EXPECT_EQ(b.started, frame == 0) << "a follow that holds is not fitted again";
            EXPECT_EQ(b.iterations, a.iterations);
            EXPECT_EQ(b.fitError, a.fitError);
        } else {
            EXPECT_GT(b.iterations, a.iterations) << "fitted again from the box: both counted";
            EXPECT_LE(b.fitError, a.fitError) << "the better of the two kept";
        }
    }
}
