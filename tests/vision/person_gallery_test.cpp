#include "vision/person_gallery.hpp"

#include <gtest/gtest.h>

namespace {

vision::FaceSignature signature(float shape, float appearance)
{
    vision::FaceSignature s;
    s.shapeUnits.fill(shape);
    s.appearanceCount = 8;
    for (int i = 0; i < s.appearanceCount; ++i)
        s.appearance[i] = appearance * static_cast<float>(i % 2 == 0 ? 1 : -1);
    s.samples = 5;
    return s;
}

}  // namespace

TEST(PersonGallery, TheNearestEnrolledPersonIsFoundAndAStrangerIsAGuest)
{
    vision::PersonGallery gallery;
    ASSERT_TRUE(gallery.enrol(1, signature(0.05f, 1.f)));
    ASSERT_TRUE(gallery.enrol(2, signature(-0.05f, -1.f)));
    EXPECT_EQ(gallery.size(), 2);

    const vision::PersonMatch one = gallery.match(signature(0.05f, 0.9f));
    EXPECT_EQ(one.personId, 1);
    EXPECT_GT(one.score, gallery.options().acceptScore);
    EXPECT_EQ(gallery.match(signature(-0.04f, -1.1f)).personId, 2);

    const vision::PersonMatch stranger = gallery.match(signature(0.3f, 4.f));
    EXPECT_EQ(stranger.personId, 0) << "nobody close enough: a guest";
    EXPECT_NE(stranger.nearestId, 0) << "but the nearest is still named, with its score";
    EXPECT_LT(stranger.nearestScore, gallery.options().acceptScore);
}

TEST(PersonGallery, EmptySignaturesBadIdsAndAFullGalleryAreRefused)
{
    vision::PersonGallery gallery;
    EXPECT_FALSE(gallery.enrol(0, signature(0.f, 0.f)));
    EXPECT_FALSE(gallery.enrol(-3, signature(0.f, 0.f)));
    EXPECT_FALSE(gallery.enrol(4, vision::FaceSignature{})) << "no samples";
    EXPECT_EQ(gallery.match(vision::FaceSignature{}).personId, 0);
    for (int id = 1; id <= vision::PersonGallery::kMaxPeople; ++id)
        ASSERT_TRUE(gallery.enrol(id, signature(0.001f * id, 0.f)));
    EXPECT_FALSE(gallery.enrol(1000, signature(0.f, 0.f))) << "full";
    EXPECT_TRUE(gallery.enrol(5, signature(0.2f, 1.f)))
        << "a known person is replaced, even when full";
}

TEST(PersonGallery, ForgetRemovesOnlyThatPerson)
{
    vision::PersonGallery gallery;
    gallery.enrol(1, signature(0.05f, 1.f));
    gallery.enrol(2, signature(-0.05f, -1.f));
    gallery.forget(1);
    EXPECT_FALSE(gallery.contains(1));
    EXPECT_TRUE(gallery.contains(2));
    EXPECT_NE(gallery.match(signature(0.05f, 1.f)).personId, 1);
    EXPECT_EQ(gallery.score(1, signature(0.05f, 1.f)), 0.f);
    gallery.clear();
    EXPECT_EQ(gallery.size(), 0);
}

TEST(PersonGallery, DifferencesCountInHowMuchEachValueVariesWithinAPerson)
{
    vision::PersonGalleryOptions options;
    options.appearanceSpread.fill(1.f);
    options.appearanceSpread[0] = 2.f;  // mode 0 varies twice as much between one's photographs
    options.shapeWeight = 0.f;
    vision::PersonGallery gallery(options);
    vision::FaceSignature enrolled = signature(0.f, 0.f);
    ASSERT_TRUE(gallery.enrol(1, enrolled));
    vision::FaceSignature alongWide = enrolled, alongNarrow = enrolled;
    alongWide.appearance[0] = 1.f;
    alongNarrow.appearance[1] = 1.f;
    EXPECT_GT(gallery.score(1, alongWide), gallery.score(1, alongNarrow));
    // d^2 = mean of the whitened squares over the 8 values: (1/2)^2 / 8 and 1 / 8.
    EXPECT_NEAR(gallery.score(1, alongWide), 1.f / (1.f + 0.25f / 8.f), 1e-5f);
    EXPECT_NEAR(gallery.score(1, alongNarrow), 1.f / (1.f + 1.f / 8.f), 1e-5f);
    vision::FaceSignature otherShape = enrolled;
    otherShape.shapeUnits.fill(1.f);
    EXPECT_EQ(gallery.score(1, otherShape), 1.f) << "shape units turned off";
}

TEST(PersonGallery, TheDefaultsAreTheMeasuredOnes)
{
    const vision::PersonGalleryOptions options;
    EXPECT_EQ(options.shapeWeight, 0.1f);
    EXPECT_EQ(options.acceptScore, 0.35f);
    EXPECT_GT(options.appearanceSpread[0], 1.f) << "the lighting-like first mode varies most";
    EXPECT_EQ(options.appearanceSpread[vision::kFaceSignatureMaxAppearance - 1], 1.f);
    for (float s : options.shapeSpread)
        EXPECT_GT(s, 0.f);
}
