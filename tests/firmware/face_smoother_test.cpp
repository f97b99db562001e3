// FaceSmoother: the faces' boxes and, with the AAM (§5.3), their fitted yaw, pitch, roll, eyes and
// size are steadied (One-Euro); a fit that does not hold passes through as not ok and its filters
// start afresh; fits are matched to faces by id and returned in the faces' order.
#include "firmware/face_smoother.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace {

vision::TrackedFace face(int id)
{
    vision::TrackedFace f;
    f.id = id;
    f.centre = {300.f, 200.f};
    f.size = 100.f;
    f.state = vision::FaceState::Confirmed;
    return f;
}

vision::FaceFit fitOf(int id, float yaw, float pitch)
{
    vision::FaceFit fit;
    fit.faceId = id;
    fit.fitted = true;
    fit.plausible = true;
    fit.outcome = vision::AamFitOutcome::Converged;
    fit.yawDegrees = yaw;
    fit.pitchDegrees = pitch;
    fit.rollDegrees = 2.f;
    fit.eyeMidpoint = {300.f, 190.f};
    fit.faceSize = 100.f;
    return fit;
}

constexpr std::int64_t kFrameNs = 33'333'333;

TEST(FaceSmoother, FittedYawAndPitchJitterIsSteadied)
{
    firmware::FaceSmoother smoother;
    const vision::TrackedFace f = face(4);
    double rawSwing = 0, smoothSwing = 0;
    float lastYaw = 0, lastPitch = 0;
    for (int frame = 0; frame < 60; ++frame) {
        const float jitter = frame % 2 == 0 ? 1.5f : -1.5f;  // +-1.5 degrees about 20 / -5
        const vision::FaceFit fit = fitOf(4, 20.f + jitter, -5.f - jitter);
        smoother.apply({&f, 1}, (frame + 1) * kFrameNs, {&fit, 1});
        ASSERT_EQ(smoother.fits().size(), 1u);
        const vision::FaceFit& out = smoother.fits()[0];
        ASSERT_TRUE(out.ok());
        if (frame >= 30) {
            rawSwing += 3.0;
            smoothSwing +=
                std::abs(out.yawDegrees - lastYaw) + std::abs(out.pitchDegrees - lastPitch);
        }
        lastYaw = out.yawDegrees;
        lastPitch = out.pitchDegrees;
    }
    EXPECT_NEAR(lastYaw, 20.f, 1.6f);
    EXPECT_NEAR(lastPitch, -5.f, 1.6f);
    EXPECT_LT(smoothSwing, 0.3 * 2 * rawSwing) << "yaw and pitch jitter mostly removed";
}

TEST(FaceSmoother, AFitThatDoesNotHoldPassesThroughAndItsFiltersStartAfresh)
{
    firmware::FaceSmoother smoother;
    const vision::TrackedFace f = face(2);
    vision::FaceFit fit = fitOf(2, 0.f, 0.f);
    for (int frame = 0; frame < 10; ++frame)
        smoother.apply({&f, 1}, (frame + 1) * kFrameNs, {&fit, 1});
    fit.outcome = vision::AamFitOutcome::Rejected;
    smoother.apply({&f, 1}, 11 * kFrameNs, {&fit, 1});
    EXPECT_FALSE(smoother.fits()[0].ok());
    // The next fit that holds is taken as it is, not pulled towards the old yaw.
    fit = fitOf(2, 25.f, 10.f);
    smoother.apply({&f, 1}, 12 * kFrameNs, {&fit, 1});
    EXPECT_TRUE(smoother.fits()[0].ok());
    EXPECT_FLOAT_EQ(smoother.fits()[0].yawDegrees, 25.f);
    EXPECT_FLOAT_EQ(smoother.fits()[0].pitchDegrees, 10.f);
}

TEST(FaceSmoother, FitsFollowTheFacesOrderByIdAndAFaceWithoutOneIsNotOk)
{
    firmware::FaceSmoother smoother;
    const vision::TrackedFace faces[3] = {face(1), face(2), face(3)};
    const vision::FaceFit fits[2] = {fitOf(3, 10.f, 0.f), fitOf(1, -10.f, 0.f)};
    smoother.apply(faces, kFrameNs, fits);
    ASSERT_EQ(smoother.fits().size(), 3u);
    EXPECT_EQ(smoother.fits()[0].faceId, 1);
    EXPECT_FLOAT_EQ(smoother.fits()[0].yawDegrees, -10.f);
    EXPECT_EQ(smoother.fits()[1].faceId, 2);
    EXPECT_FALSE(smoother.fits()[1].ok());
    EXPECT_EQ(smoother.fits()[2].faceId, 3);
    EXPECT_FLOAT_EQ(smoother.fits()[2].yawDegrees, 10.f);
    // Without fits (no model) every face has none.
    smoother.apply(faces, 2 * kFrameNs);
    for (const vision::FaceFit& fit : smoother.fits())
        EXPECT_FALSE(fit.ok());
}

}  // namespace
