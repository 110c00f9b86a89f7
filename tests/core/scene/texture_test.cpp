// Image decoding and texture filtering: lookups over a footprint (MIP levels, trilinear)
// average what the footprint covers; the point lookup agrees with it at a point.
#include "core/scene/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/scene/texture_filter.h"
#include "core/scene_io/image_decode.h"
#include "core/scene_io/scene_files.h"
#include "tests/support/png_fixture.h"
#include "tests/support/test_env.h"

namespace pf {
namespace {

// A 64x64 8-bit checkerboard of single texels, black and white, encoded as PNG.
std::string CheckerboardPng() {
    std::vector<unsigned char> pixels(64 * 64 * 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) pixels[(y * 64 + x) * 3 + c] = (x + y) % 2 ? 255 : 0;
    return testing::PngOf(64, 64, 3, pixels.data());
}

// An RGBA PNG of `values` (4 per texel, colour as given), 8- or 16-bit as they are, its bytes.
std::string RgbaPng(const std::vector<uint8_t>& values) {
    return testing::PngOf(static_cast<int>(values.size() / 4), 1, 4, values.data());
}
std::string RgbaPng(const std::vector<uint16_t>& values) {
    return testing::SixteenBitPngOf(static_cast<int>(values.size() / 4), 1, 4, values.data());
}

// The sRGB transfer function (IEC 61966-2-1), written here in double precision.
double SrgbDecoded(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

TEST(TextureTest, EightAndSixteenBitCodesDecodeAsTheTransferFunctionSays) {
    // 8- and 16-bit images are decoded through a table of their codes: every channel, the
    // green alone, alpha (linear), and a gamma, against the formulas.
    const std::vector<uint8_t> bytes8 = {0, 10, 128, 255, 255, 200, 3, 51};
    const std::vector<uint16_t> codes16 = {0, 1000, 40000, 65535, 65535, 12345, 777, 13107};
    for (int bits : {8, 16}) {
        const std::string png = bits == 8 ? RgbaPng(bytes8) : RgbaPng(codes16);
        const auto value = [&](int k) {
            return bits == 8 ? bytes8[k] / 255.0 : codes16[k] / 65535.0;
        };
        const absl::StatusOr<Texture> colour = DecodeImage(png, "codes.png", SceneLimits{});
        ASSERT_TRUE(colour.ok()) << colour.status();
        ASSERT_EQ(colour->texels.size(), 2u);
        for (int texel = 0; texel < 2; ++texel)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(colour->texels[texel][c], SrgbDecoded(value(4 * texel + c)), 2e-6)
                    << bits << " bits, texel " << texel << ", channel " << c;
        ImageDecodeOptions options;
        options.channels = ImageChannels::kGreen;
        options.encoding = ImageEncoding::kGamma;
        options.gamma = 1.8;
        const absl::StatusOr<Texture> green = DecodeImage(png, "codes.png", SceneLimits{}, options);
        ASSERT_TRUE(green.ok()) << green.status();
        EXPECT_NEAR(green->texels[1].x, std::pow(value(5), 1.8), 2e-6) << bits << " bits";
        options.channels = ImageChannels::kAlpha;
        const absl::StatusOr<Texture> alpha = DecodeImage(png, "codes.png", SceneLimits{}, options);
        ASSERT_TRUE(alpha.ok()) << alpha.status();
        EXPECT_NEAR(alpha->texels[0].x, value(3), 1e-7) << bits << " bits";
        EXPECT_NEAR(alpha->texels[1].x, value(7), 1e-7) << bits << " bits";
    }
}

TEST(TextureTest, FootprintsAverageWhatTheyCover) {
    absl::StatusOr<Texture> texture = DecodeImage(CheckerboardPng(), "checks.png", SceneLimits{});
    ASSERT_TRUE(texture.ok()) << texture.status();
    const auto shared = std::make_shared<const Texture>(std::move(*texture));
    const std::shared_ptr<const TextureFilter> filter = MakeTextureFilter({shared});
    // At a texel's centre, a footprint below a texel sees that texel; one many texels wide sees
    // the average (a fine checkerboard's is half white), as the bilinear point sample (the
    // photons' lookup) does not.
    const float u = 0.5f / 64, v = 0.5f / 64;  // texel (0, 0): black
    EXPECT_NEAR(filter->Sample(0, u, v, 0.0f).x, 0.0f, 1e-6f);
    EXPECT_NEAR(shared->Sample(u, v).x, 0.0f, 1e-6f);
    EXPECT_NEAR(filter->Sample(0, u + 1.0f / 64, v, 0.0f).x, 1.0f, 1e-6f);  // its neighbour: white
    for (float footprint : {4.0f / 64, 8.0f / 64, 0.5f, 1000.0f})  // up to past the coarsest level
        EXPECT_NEAR(filter->Sample(0, u, v, footprint).x, 0.5f, 0.02f) << footprint;
}

TEST(TextureTest, PointLookupsAgreeWithTheFiltersFinestLevelAndWrap) {
    // A smooth image (no level choice matters at a zero footprint): the point lookup the photons
    // and the Vulkan kernels use and the filter's finest level are the same bilinear lookup,
    // repeat-wrapped past [0, 1).
    auto texture = std::make_shared<Texture>();
    texture->width = 5, texture->height = 3;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
            texture->texels.push_back(Rgb(0.1f * x, 0.3f * y, 0.05f * (x + y)));
    const std::shared_ptr<const TextureFilter> filter = MakeTextureFilter({texture});
    for (const auto& [u, v] :
         {std::pair{0.13f, 0.71f}, {0.5f, 0.5f}, {0.95f, 0.02f}, {1.3f, -0.4f}, {-2.7f, 3.2f}}) {
        const Rgb point = texture->Sample(u, v), filtered = filter->Sample(0, u, v, 0.0f);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(filtered[c], point[c], 1e-5f) << u << ", " << v;
    }
}

TEST(TextureTest, WrapModesAddressBeyondTheImageAsGltfAndPbrtSay) {
    // Texels 0..3 along an axis of 4: repeat, the edge (clamp), mirrored, or black.
    const int32_t repeat[] = {2, 3, 0, 1, 2, 3, 0, 1}, clamp[] = {0, 0, 0, 1, 2, 3, 3, 3},
                  mirror[] = {1, 0, 0, 1, 2, 3, 3, 2}, black[] = {-1, -1, 0, 1, 2, 3, -1, -1};
    for (int i = -2; i < 6; ++i) {
        EXPECT_EQ(gpu::WrapTexel(i, 4, gpu::kWrapRepeat), repeat[i + 2]) << i;
        EXPECT_EQ(gpu::WrapTexel(i, 4, gpu::kWrapClamp), clamp[i + 2]) << i;
        EXPECT_EQ(gpu::WrapTexel(i, 4, gpu::kWrapMirror), mirror[i + 2]) << i;
        EXPECT_EQ(gpu::WrapTexel(i, 4, gpu::kWrapBlack), black[i + 2]) << i;
    }
    EXPECT_EQ(gpu::WrapTexel(-9, 4, gpu::kWrapMirror), 0) << "mirrored: i reads as i + 8 does";
    // A 2x1 image, white then grey: past its right edge, clamp stays grey, repeat goes back to
    // white, black fades to black; u and v are wrapped each as their own mode says.
    Texture texture;
    texture.width = 2, texture.height = 1;
    texture.texels = {Rgb(1.0f), Rgb(0.5f)};
    texture.wrap_u = gpu::kWrapClamp;
    EXPECT_NEAR(texture.Sample(1.5f, 0.5f).x, 0.5f, 1e-6f);
    texture.wrap_u = gpu::kWrapRepeat;
    EXPECT_NEAR(texture.Sample(1.0f, 0.5f).x, 0.75f, 1e-6f);
    texture.wrap_u = gpu::kWrapBlack;
    EXPECT_NEAR(texture.Sample(1.0f, 0.5f).x, 0.25f, 1e-6f);
    EXPECT_NEAR(texture.Sample(0.5f, 7.3f).x, 0.75f, 1e-6f) << "v repeats";
}

TEST(TextureTest, OctahedralWrapCrossesToWhereTheSphereContinues) {
    // pbrt-v4's octahedralsphere on a 4x4 image: across the left or right edge, x mirrors
    // there and y flips; across the top or bottom, y mirrors and x flips; both, at a corner.
    const auto wrapped = [](int32_t x, int32_t y) {
        gpu::WrapTexels(x, y, 4, 4, gpu::kWrapOctahedral, gpu::kWrapOctahedral);
        return std::pair{x, y};
    };
    EXPECT_EQ(wrapped(2, 1), (std::pair{2, 1})) << "inside: itself";
    EXPECT_EQ(wrapped(-1, 1), (std::pair{0, 2}));
    EXPECT_EQ(wrapped(4, 0), (std::pair{3, 3}));
    EXPECT_EQ(wrapped(1, -1), (std::pair{2, 0}));
    EXPECT_EQ(wrapped(3, 4), (std::pair{0, 3}));
    EXPECT_EQ(wrapped(-1, -1), (std::pair{3, 3})) << "a corner: the opposite one";
    // The lookup: a 2x2 image of four colours read half a texel past its left edge at the top
    // row's centre blends the top-left texel with the bottom-left one (where the sphere goes on).
    Texture texture;
    texture.width = texture.height = 2;
    texture.texels = {Rgb(1, 0, 0), Rgb(0, 1, 0), Rgb(0, 0, 1), Rgb(1, 1, 1)};
    texture.wrap_u = texture.wrap_v = gpu::kWrapOctahedral;
    const Rgb left = texture.Sample(0.0f, 0.25f);
    EXPECT_NEAR(left.x, 0.5f, 1e-6f);
    EXPECT_NEAR(left.z, 0.5f, 1e-6f);
    EXPECT_NEAR(left.y, 0.0f, 1e-6f);
}

TEST(TextureTest, FiltersKeepTheirOwnTextures) {
    // Scenes come and go in a coordinator: each filter's textures are its own, and a filter
    // outlived by another leaves that one's lookups intact.
    const auto solid = [](float value) {
        auto texture = std::make_shared<Texture>();
        texture->width = texture->height = 2;
        texture->texels.assign(4, Rgb(value));
        return texture;
    };
    const std::shared_ptr<const TextureFilter> kept = MakeTextureFilter({solid(0.25f)});
    EXPECT_NEAR(kept->Sample(0, 0.3f, 0.6f, 0.1f).x, 0.25f, 1e-6f);
    for (int i = 0; i < 3; ++i) {
        const std::shared_ptr<const TextureFilter> passing = MakeTextureFilter({solid(0.5f + i)});
        EXPECT_NEAR(passing->Sample(0, 0.3f, 0.6f, 0.1f).x, 0.5f + i, 1e-6f);
    }
    EXPECT_NEAR(kept->Sample(0, 0.7f, 0.1f, 0.5f).x, 0.25f, 1e-6f);
}

}  // namespace
}  // namespace pf
