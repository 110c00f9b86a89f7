// Image decoding and texture filtering: the MIP pyramid OpenImageIO resamples, and lookups
// over a footprint that average what the footprint covers.
#include "core/scene/texture.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "core/scene/image_decode.h"
#include "core/scene/scene_files.h"

namespace pf {
namespace {

// A 64x64 8-bit checkerboard of single texels, black and white, encoded as PNG.
std::string CheckerboardPng() {
    std::vector<unsigned char> pixels(64 * 64 * 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) pixels[(y * 64 + x) * 3 + c] = (x + y) % 2 ? 255 : 0;
    const std::string path = (std::filesystem::temp_directory_path() / "photonfarm-checkerboard.png").string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(64, 64, 3, OIIO::TypeDesc::UINT8)));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
    const absl::StatusOr<std::string> bytes = ReadWholeFile(path);
    std::filesystem::remove(path);
    return bytes.ok() ? *bytes : std::string();
}

TEST(TextureTest, PyramidHalvesDownToOneTexelAndKeepsTheMean) {
    const absl::StatusOr<Texture> texture = DecodeImage(CheckerboardPng(), "checks.png", SceneLimits{});
    ASSERT_TRUE(texture.ok()) << texture.status();
    ASSERT_EQ(texture->mips.size(), 6u);  // 32, 16, 8, 4, 2, 1
    EXPECT_EQ(texture->mips.back().width, 1);
    // A fine checkerboard's average is half white; every coarser level shows that grey.
    for (const TextureLevel& level : texture->mips)
        for (const Rgb& texel : level.texels) ASSERT_NEAR(texel.x, 0.5f, 0.02f) << level.width;
}

TEST(TextureTest, FootprintsAverageWhatTheyCover) {
    const absl::StatusOr<Texture> texture = DecodeImage(CheckerboardPng(), "checks.png", SceneLimits{});
    ASSERT_TRUE(texture.ok()) << texture.status();
    // At a texel's centre, a footprint below a texel sees that texel; one many texels wide sees
    // the average, as the bilinear point sample (the photons' lookup) does not.
    const float u = 0.5f / 64, v = 0.5f / 64;  // texel (0, 0): black
    EXPECT_NEAR(texture->SampleFiltered(u, v, 0.5f / 64).x, 0.0f, 1e-6f);
    EXPECT_NEAR(texture->Sample(u, v).x, 0.0f, 1e-6f);
    EXPECT_NEAR(texture->SampleFiltered(u, v, 8.0f / 64).x, 0.5f, 0.02f);
    EXPECT_NEAR(texture->SampleFiltered(u, v, 1000.0f).x, 0.5f, 0.02f);  // past the coarsest level
}

}  // namespace
}  // namespace pf
