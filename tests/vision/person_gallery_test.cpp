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
    EXPECT_TRUE(gallery.enrol(5, signature(0.2f, 1.f))) << "a known person is replaced, even when full";
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
