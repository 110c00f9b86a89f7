// Blobs survive encoding bit for bit; truncated, corrupt or mismatched blobs are refused.
#include "wire/blob_codec.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <random>

namespace pf {
namespace {

TEST(BlobCodecTest, FloatsAndHitPointsRoundTripExactly) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uniform(-1e6f, 1e6f);
    std::vector<float> floats(10007);
    for (float& value : floats) value = uniform(rng);
    floats[0] = 0.0f;
    floats[1] = -0.0f;
    floats[2] = std::numeric_limits<float>::denorm_min();
    const absl::StatusOr<std::vector<float>> decoded =
        DecodeFloats(EncodeFloats(floats), floats.size());
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_EQ(std::memcmp(decoded->data(), floats.data(), floats.size() * 4), 0);

    std::vector<HitPoint> hit_points(999);
    for (size_t i = 0; i < hit_points.size(); ++i)
        hit_points[i] = {Vec3(uniform(rng), uniform(rng), uniform(rng)), Vec3(0, 0, 1),
                         Rgb(0.1f * i), uint32_t(i * 7)};
    const absl::StatusOr<std::vector<HitPoint>> back =
        DecodeHitPoints(EncodeHitPoints(hit_points), hit_points.size());
    ASSERT_TRUE(back.ok()) << back.status();
    // What workers read comes back bit for bit, the pixel and coat included; what a hit point
    // gathers is not sent (ppm's gather the default).
    for (size_t i = 0; i < hit_points.size(); ++i)
        ASSERT_EQ(std::memcmp(&(*back)[i], &hit_points[i], offsetof(HitPoint, gathers)), 0) << i;
}

TEST(BlobCodecTest, SquaredRadiiCompressWell) {
    // Radii of one epoch vary smoothly around R0^2: the byte planes compress them well.
    std::vector<float> radius_sq(1 << 16);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> shrink(0.5f, 1.0f);
    for (float& value : radius_sq) value = 2.25e-6f * shrink(rng);
    const std::string bytes = EncodeFloats(radius_sq);
    EXPECT_LT(bytes.size(), radius_sq.size() * 3.5) << "at most 3.5 bytes per hit point";
}

TEST(BlobCodecTest, DamagedBlobsAreRefused) {
    const std::vector<float> floats(1000, 1.5f);
    const std::string bytes = EncodeFloats(floats);
    EXPECT_FALSE(DecodeFloats(bytes, 999).ok()) << "a blob for another job's hit point count";
    EXPECT_FALSE(DecodeFloats(bytes.substr(0, bytes.size() / 2), 1000).ok()) << "truncated";
    EXPECT_FALSE(DecodeFloats(bytes.substr(0, 4), 1000).ok()) << "no header";
    std::string corrupt = bytes;
    corrupt[corrupt.size() / 2] ^= 0x5a;
    corrupt[9] ^= 0x77;
    EXPECT_FALSE(DecodeFloats(corrupt, 1000).ok());
    EXPECT_FALSE(DecodeImagePixels(bytes, 1 << 20, 1 << 20).ok()) << "an image over the size limit";
}

TEST(BlobCodecTest, BlobDigestIsSha256OfTheBytes) {
    EXPECT_EQ(Blob::Of("abc").digest,
              "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

}  // namespace
}  // namespace pf
