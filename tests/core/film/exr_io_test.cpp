// EXR output: float RGB round-trips exactly, with its metadata; failures are one clear line.
#include "core/film/exr_io.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/test_env.h"

namespace pf {
namespace {

TEST(ExrIoTest, FloatRgbAndMetadataRoundTripExactly) {
    Image image(5, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = Rgb(0.1f * i, 1e-30f * i, 3e30f);
    const std::string path = testing::TempPath("pf-exr-roundtrip.exr");
    ASSERT_TRUE(
        WriteExr(path, image, {{"photonfarm:seed", "42"}, {"photonfarm:scene", "a.gltf"}}).ok());
    ImageMetadata metadata;
    const absl::StatusOr<Image> read = ReadExr(path, &metadata);
    ASSERT_TRUE(read.ok()) << read.status();
    EXPECT_EQ(read->width, 5);
    EXPECT_EQ(read->height, 3);
    EXPECT_EQ(read->pixels, image.pixels);
    EXPECT_EQ(metadata["photonfarm:seed"], "42");
    EXPECT_EQ(metadata["photonfarm:scene"], "a.gltf");
    EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(ExrIoTest, UnwritablePathFailsWithTheFileNamed) {
    const absl::Status status = WriteExr("/nonexistent-dir/x.exr", Image(2, 2));
    ASSERT_FALSE(status.ok());
    EXPECT_NE(std::string(status.message()).find("/nonexistent-dir/x.exr"), std::string::npos);
}

TEST(ExrIoTest, NonExrFileIsRefused) {
    const std::string path = testing::TempPath("pf-not-an.exr");
    FILE* file = std::fopen(path.c_str(), "w");
    std::fputs("not an image", file);
    std::fclose(file);
    EXPECT_FALSE(ReadExr(path).ok());
}

}  // namespace
}  // namespace pf
