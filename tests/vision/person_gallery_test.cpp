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
    EXPECT_EQ(options.shapeWeight, 0.5f);
    EXPECT_EQ(options.textureWeight, 10.f);
    EXPECT_EQ(options.textureSpread, 7.f);
    EXPECT_EQ(options.acceptScore, 0.33f);
    EXPECT_GT(options.appearanceSpread[0], 1.f) << "the lighting-like first mode varies most";
    EXPECT_EQ(options.appearanceSpread[vision::kFaceSignatureMaxAppearance - 1], 1.f);
    for (float s : options.shapeSpread)
        EXPECT_GT(s, 0.f);
}

// The texture descriptor's part: off at weight 0; at a weight, its Hellinger distance (in units
// of textureSpread) decides between persons the other parts cannot tell apart; descriptors of
// different sizes (another grid) are not compared.
TEST(PersonGallery, TheTextureCountsAtItsWeightInItsSpreadsUnits)
{
    auto withTexture = [](std::uint8_t level) {
        vision::FaceSignature s = signature(0.f, 0.5f);
        s.textureCount = 16 * vision::kAamLbpBins;
        for (int i = 0; i < s.textureCount; ++i)
            s.texture[static_cast<std::size_t>(i)] =
                static_cast<std::uint8_t>(i % 3 == 0 ? level : 255 - level);
        return s;
    };
    vision::PersonGalleryOptions options;
    options.textureWeight = 0.f;
    vision::PersonGallery gallery(options);
    gallery.enrol(1, withTexture(40));
    gallery.enrol(2, withTexture(200));
    const vision::FaceSignature probe = withTexture(190);
    EXPECT_FLOAT_EQ(gallery.score(1, probe), gallery.score(2, probe)) << "weight 0: ignored";

    options.textureWeight = 1.f;
    options.textureSpread = 10.f;
    gallery.setOptions(options);
    EXPECT_EQ(gallery.match(probe).nearestId, 2);
    // Every value 10 apart, one spread: the texture part's mean square is 1 (the shape and
    // appearance parts are 0: identical), d^2 the weighted mean of the three parts.
    EXPECT_NEAR(gallery.score(2, probe),
                1.f / (1.f + 1.f / (options.shapeWeight + 1.f + options.textureWeight)), 1e-5f);
    vision::FaceSignature otherGrid = probe;
    otherGrid.textureCount = 25 * vision::kAamLbpBins;
    options.shapeWeight = 0.f;
    gallery.setOptions(options);
    EXPECT_FLOAT_EQ(gallery.score(1, otherGrid), gallery.score(2, otherGrid))
        << "another grid's descriptor is not compared";
}
