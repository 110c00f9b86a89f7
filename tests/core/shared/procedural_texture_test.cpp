// pbrt-v4's noise and procedural textures (core/shared/noise.h, procedural_texture.h) at fixed
// points against its formulas, written again here: Perlin noise as a sum over its cell's eight
// corners, FBm and Turbulence as sums of octaves, the checkerboard's filter as an integral,
// dots at their centres, marble's spline by de Casteljau's construction, and the programs'
// instructions one by one.
#include "core/shared/procedural_texture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <random>
#include <vector>

#include "core/scene/texture_program.h"
#include "core/shared/noise.h"

namespace pf {
namespace {

// Perlin's published permutation begins 151 160 137 91 90 15 and ends 61 156 180.
TEST(NoiseTest, ThePermutationIsPerlins) {
    std::array<int, 256> seen{};
    for (int i = 0; i < 256; ++i) ++seen[gpu::kNoisePermutation[i]];
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
    EXPECT_EQ(gpu::kNoisePermutation[0], 151);
    EXPECT_EQ(gpu::kNoisePermutation[5], 15);
    EXPECT_EQ(gpu::kNoisePermutation[255], 180);
    EXPECT_EQ(gpu::NoisePermutation(256), 151) << "the table repeats";
}

// pbrt-v4's gradient of lattice point (x, y, z): its hash's low four bits h pick u (x for h < 8,
// 12 and 13, else y) and v (y for h < 4, 12 and 13, else z), each negated by a bit of h.
Vec3 Gradient(int x, int y, int z) {
    const auto p = [](int i) { return gpu::kNoisePermutation[i & 255]; };
    const int h = p(p(p(x) + y) + z) & 15;
    const int u = h < 8 || h == 12 || h == 13 ? 0 : 1;
    const int v = h < 4 || h == 12 || h == 13 ? 1 : 2;
    Vec3 g(0.0f);
    g[u] += (h & 1) ? -1.0f : 1.0f;
    g[v] += (h & 2) ? -1.0f : 1.0f;
    return g;
}

// Perlin noise as the sum over the cell's corners c of w(c) g(c) . (p - c), w the product of
// the quintic fade s(t) = 6t^5 - 15t^4 + 10t^3 toward each corner.
double NoiseBySum(const Vec3d& p) {
    const Vec3d cell(std::floor(p.x), std::floor(p.y), std::floor(p.z));
    const Vec3d d = p - cell;
    const auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
    double sum = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const int cx = corner & 1, cy = (corner >> 1) & 1, cz = corner >> 2;
        const Vec3 g = Gradient(int(cell.x) + cx, int(cell.y) + cy, int(cell.z) + cz);
        const Vec3d offset(d.x - cx, d.y - cy, d.z - cz);
        const double w = (cx ? fade(d.x) : 1 - fade(d.x)) * (cy ? fade(d.y) : 1 - fade(d.y)) *
                         (cz ? fade(d.z) : 1 - fade(d.z));
        sum += w * (g.x * offset.x + g.y * offset.y + g.z * offset.z);
    }
    return sum;
}

TEST(NoiseTest, PerlinNoiseIsItsCornersWeightedSum) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coordinate(-300.0f, 300.0f);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        ASSERT_NEAR(gpu::PerlinNoise(p), NoiseBySum(Vec3d(p)), 2e-5) << p.x << " " << p.y;
    }
}

TEST(NoiseTest, NoiseIsZeroAtTheLatticeWhereItsSlopeIsTheGradient) {
    for (int x = -3; x < 260; x += 37)
        for (int y = -5; y < 40; y += 11)
            for (int z = -2; z < 6; z += 3) {
                const Vec3 p{float(x), float(y), float(z)};
                ASSERT_EQ(gpu::PerlinNoise(p), 0.0f) << x << " " << y << " " << z;
                const float h = 1e-2f;  // float rounding at x ~ 256 is 1e-5
                const Vec3 g = Gradient(x, y, z);
                for (int axis = 0; axis < 3; ++axis) {
                    Vec3 step(0.0f);
                    step[axis] = h;
                    const float slope =
                        (gpu::PerlinNoise(p + step) - gpu::PerlinNoise(p - step)) / (2 * h);
                    EXPECT_NEAR(slope, g[axis], 3e-3f) << x << " " << y << " " << z << " " << axis;
                }
            }
    // Far out, where a float is a multiple of 256, the coordinates are taken modulo 2^30 first,
    // so that their cells are int32s (noise's period is 256 anyway).
    for (const float far : {4294967296.0f, -3221225472.0f, 1e20f})
        EXPECT_EQ(gpu::PerlinNoise(Vec3(far, 0.25f, 0.75f)),
                  gpu::PerlinNoise(Vec3(0.0f, 0.25f, 0.75f)))
            << far;
}

// The footprint whose octave count is n: n = -1 - log2(footprint).
float FootprintSq(float n) {
    const float footprint = std::exp2(-1 - n);
    return footprint * footprint;
}

TEST(NoiseTest, FbmAndTurbulenceSumTheOctavesPbrtSums) {
    const Vec3 p(0.37f, -1.21f, 2.68f);
    const auto noise = [&](int octave) {
        return gpu::PerlinNoise(p * std::pow(1.99f, float(octave)));
    };
    const float omega = 0.6f;
    // A point: all 5 octaves; FBm's partial octave fades out at 0.
    double fbm = 0, turbulence = 0;
    for (int i = 0; i < 5; ++i) {
        fbm += std::pow(omega, i) * noise(i);
        turbulence += std::pow(omega, i) * std::abs(noise(i));
    }
    EXPECT_NEAR(gpu::FractalNoise(p, 0.0f, omega, 5), fbm, 1e-5);
    // Turbulence counts 0.2 for the partial octave (pbrt-v4's Lerp(0, 0.2, |noise|)).
    EXPECT_NEAR(gpu::Turbulence(p, 0.0f, omega, 5), turbulence + 0.2 * std::pow(omega, 5), 1e-5);
    // A footprint resolving 2.5 octaves: two whole, the third at SmoothStep(0.5, 0.3, 0.7) =
    // 1/2; turbulence's unresolved octaves 0.2 each, the first of them at the partial's weight.
    const float sq = FootprintSq(2.5f);
    EXPECT_NEAR(gpu::FractalNoise(p, sq, omega, 5),
                noise(0) + omega * noise(1) + omega * omega * 0.5 * noise(2), 1e-5);
    EXPECT_NEAR(gpu::Turbulence(p, sq, omega, 5),
                std::abs(noise(0)) + omega * std::abs(noise(1)) +
                    omega * omega * (0.5 * 0.2 + 0.5 * std::abs(noise(2))) +
                    0.2 * (omega * omega + std::pow(omega, 3) + std::pow(omega, 4)),
                1e-5);
    // A footprint wider than the noise: no octave; turbulence is its 0.2s.
    EXPECT_EQ(gpu::FractalNoise(p, 100.0f, omega, 5), 0.0f);
    EXPECT_NEAR(gpu::Turbulence(p, 100.0f, omega, 5),
                0.2 * (2 + omega + omega * omega + std::pow(omega, 3) + std::pow(omega, 4)), 1e-5);
}

// A program's value at `at`, its images read by `images`.
class NoImages final : public gpu::TextureImages {
public:
    gpu::vec3 ImageValue(int32_t texture, gpu::vec2 uv, float width) const override {
        // Image t's value: (t, u, v), and the footprint in the blue channel's place.
        return {float(texture) + width, uv.x, uv.y};
    }
};

Rgb Evaluate(const std::vector<gpu::vec4>& program, const gpu::TextureLookup& at) {
    return gpu::EvaluateProceduralTexture(program.data(), uint32_t(program.size()), at, NoImages());
}

gpu::TextureLookup At(const Vec3& position, const Point2& uv = {}, const Vec3& normal = {0, 0, 1},
                      float width = 0, float uv_width = 0) {
    return {position, normal, uv, width, uv_width};
}

bool Near(const Rgb& a, const Rgb& b, float tolerance = 1e-5f) {
    return std::abs(a.x - b.x) <= tolerance && std::abs(a.y - b.y) <= tolerance &&
           std::abs(a.z - b.z) <= tolerance;
}

TEST(ProceduralTextureTest, CheckerboardFilterIsTheSquareWavesMeanUnderATriangle) {
    // pbrt-v4's checkerboard along one axis: +1 on even cells, -1 on odd; filtered, the square
    // wave's mean under a triangle of half-width r (its integral d's second difference).
    const auto square = [](double x) { return (int64_t(std::floor(x)) & 1) ? -1.0 : 1.0; };
    for (const double x : {0.25, 0.9, 1.1, -0.05, 3.5, -2.7})
        for (const double r : {0.0, 0.05, 0.3, 0.8, 2.5}) {
            double expected = square(x);
            if (r > 0) {
                const int steps = 20000;
                double sum = 0, weights = 0;
                for (int i = 0; i < steps; ++i) {
                    const double t = -r + 2 * r * (i + 0.5) / steps;
                    const double w = 1 - std::abs(t) / r;
                    sum += w * square(x + t), weights += w;
                }
                expected = sum / weights;
            }
            EXPECT_NEAR(gpu::CheckerAxis(float(x), float(r)), expected, 2e-3) << x << " " << r;
        }
}

TEST(ProceduralTextureTest, DotsLieAtTheirNoiseMovedCentres) {
    // Cell (s, t) (the unit square about integers s and t) holds a dot where noise(s + 1/2,
    // t + 1/2, 1/2) > 0, of radius 0.35 about (s, t) + 0.15 (noise(s + 1.5, t + 2.8, 1/2),
    // noise(s + 4.5, t + 9.8, 1/2)).
    const auto noise = [](float x, float y) { return gpu::PerlinNoise(Vec3(x, y, 0.5f)); };
    const auto centre = [&](int s, int t) {
        return Point2(s + 0.15f * noise(s + 1.5f, t + 2.8f), t + 0.15f * noise(s + 4.5f, t + 9.8f));
    };
    const auto inside = [&](Point2 st) {
        const int s = int(std::floor(st.x + 0.5f)), t = int(std::floor(st.y + 0.5f));
        if (!(noise(s + 0.5f, t + 0.5f) > 0)) return false;
        const Point2 c = centre(s, t);
        return (st.x - c.x) * (st.x - c.x) + (st.y - c.y) * (st.y - c.y) < 0.35f * 0.35f;
    };
    int with = 0, without = 0, outside = 0;
    for (int s = -6; s < 6; ++s)
        for (int t = -6; t < 6; ++t) {
            const Point2 c = centre(s, t);
            if (noise(s + 0.5f, t + 0.5f) > 0) {
                ++with;
                EXPECT_TRUE(gpu::InsideDot(c)) << s << " " << t;
            } else {
                ++without;
                EXPECT_FALSE(gpu::InsideDot(c)) << s << " " << t;
            }
            for (const Point2 d : {Point2(0.34f, 0), Point2(0, -0.34f), Point2(0.36f, 0),
                                   Point2(-0.25f, 0.26f), Point2(0.1f, 0.2f)}) {
                const Point2 st(c.x + d.x, c.y + d.y);
                EXPECT_EQ(gpu::InsideDot(st), inside(st)) << st.x << " " << st.y;
                outside += !inside(st);
            }
        }
    EXPECT_GT(with, 20);
    EXPECT_GT(without, 20);
    EXPECT_GT(outside, with * 2) << "points outside dots were tested too";
}

TEST(ProceduralTextureTest, MarbleIsItsSplineOfTheSineOfFbm) {
    // pbrt-v4's marble: t = 1/2 + sin(p.y + variation FBm(p)) / 2 picks one of six cubic Bezier
    // segments of its nine colours (three apart), times 1.5; de Casteljau's construction here.
    const Rgb colours[9] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                            {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                            {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coordinate(-4.0f, 4.0f);
    for (int i = 0; i < 200; ++i) {
        const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        const float marble = p.y + 0.7f * gpu::FractalNoise(p, 0.0f, 0.4f, 6);
        float t = 0.5f + 0.5f * std::sin(marble);
        const int first = std::min(int(std::floor(t * 6)), 5);
        t = t * 6 - first;
        Rgb c[4];
        std::copy(colours + first, colours + first + 4, c);
        for (int level = 3; level > 0; --level)
            for (int k = 0; k < level; ++k) c[k] = c[k] * (1 - t) + c[k + 1] * t;
        ASSERT_TRUE(Near(gpu::MarbleColourAt(p, 0.0f, 0.4f, 6, 0.7f), c[0] * 1.5f)) << i;
    }
}

TEST(ProceduralTextureTest, WindyIsStrengthTimesWaves) {
    const Vec3 p(3.1f, -0.4f, 7.7f);
    EXPECT_NEAR(
        gpu::WindyNoise(p, 0.0f),
        std::abs(gpu::FractalNoise(p * 0.1f, 0.0f, 0.5f, 3)) * gpu::FractalNoise(p, 0.0f, 0.5f, 6),
        1e-6f);
}

TEST(ProceduralTextureTest, ProgramsEvaluateEachInstruction) {
    std::vector<gpu::vec4> program;
    TextureProgramWriter write(&program);
    const auto reset = [&] { program.clear(); };
    const double identity[6] = {1, 0, 0, 0, 1, 0};
    // Constants, multiplied and mixed.
    write.Constant({0.2f, 0.4f, 0.6f});
    write.Constant(Rgb(0.5f));
    write.Combine(gpu::kTextureMultiply);
    EXPECT_TRUE(Near(Evaluate(program, At({})), {0.1f, 0.2f, 0.3f}));
    reset();
    write.Constant(Rgb(1.0f));
    write.Constant({0.0f, 0.5f, 0.0f});
    write.Constant(Rgb(0.25f));
    write.Combine(gpu::kTextureMix);
    EXPECT_TRUE(Near(Evaluate(program, At({})), {0.75f, 0.875f, 0.75f}));
    // directionmix: |n . d| of the first.
    reset();
    write.Constant(Rgb(1.0f));
    write.Constant(Rgb(0.0f));
    write.DirectionMix(Normalize(Vec3(0, 1, 1)));
    EXPECT_TRUE(Near(Evaluate(program, At({}, {}, {0, 0, -1})), Rgb(std::sqrt(0.5f))));
    // An image through a UV transform, its footprint scaled by the transform's.
    reset();
    const double scaled[6] = {2, 0, 0.5, 0, 2, -1};
    write.Image(7, scaled);
    EXPECT_TRUE(
        Near(Evaluate(program, At({}, {0.25f, 0.5f}, {0, 0, 1}, 0, 0.01f)), {7.02f, 1.0f, 0.0f}));
    // Checkerboard at (s, t) = (4u, 4v): tex1 on even checks, tex2 on odd ones.
    reset();
    write.Constant(Rgb(0.9f));
    write.Constant(Rgb(0.1f));
    const double four[6] = {4, 0, 0, 0, 4, 0};
    write.Planar(gpu::kTextureCheckerboard, four);
    EXPECT_TRUE(Near(Evaluate(program, At({}, {0.1f, 0.1f})), Rgb(0.9f)));
    EXPECT_TRUE(Near(Evaluate(program, At({}, {0.3f, 0.1f})), Rgb(0.1f)));
    EXPECT_TRUE(Near(Evaluate(program, At({}, {0.3f, 0.3f})), Rgb(0.9f)));
    EXPECT_TRUE(Near(Evaluate(program, At({}, {-0.1f, 0.1f})), Rgb(0.1f)));
    // Filtered over a footprint wider than many checks: their mean.
    EXPECT_TRUE(Near(Evaluate(program, At({}, {0.1f, 0.1f}, {}, 0, 3.0f)), Rgb(0.5f), 0.02f));
    // Bilerp: v00 (1 - s)(1 - t) + v10 s (1 - t) + v01 (1 - s) t + v11 s t, beyond [0, 1] too.
    reset();
    write.Bilerp(identity, Rgb(0.1f), Rgb(0.3f), Rgb(0.5f), Rgb(0.9f));
    for (const auto& [s, t] : {std::pair{0.25f, 0.5f}, std::pair{1.5f, -0.5f}}) {
        const float expected =
            0.1f * (1 - s) * (1 - t) + 0.5f * s * (1 - t) + 0.3f * (1 - s) * t + 0.9f * s * t;
        EXPECT_TRUE(Near(Evaluate(program, At({}, {s, t})), Rgb(expected)));
    }
    // Noise in the texture's space (here x2 and moved), raised to a power, clamped.
    reset();
    Transform texture_from_world = Transform::Translate({1, 2, 3});
    for (int i = 0; i < 3; ++i) texture_from_world.m[i][i] = 2;
    write.Solid(gpu::kTextureWrinkled, texture_from_world, 0.5f, 8);
    write.Power(0.5f);
    const Vec3 p(0.3f, 0.1f, -0.2f), q = p * 2.0f + Vec3(1, 2, 3);
    EXPECT_TRUE(Near(Evaluate(program, At(p)), Rgb(std::sqrt(gpu::Turbulence(q, 0.0f, 0.5f, 8)))));
    // The footprint, scaled by the transform: 2 x 0.01 resolves -1 - log2(0.02) octaves.
    EXPECT_TRUE(Near(Evaluate(program, At(p, {}, {}, 0.01f)),
                     Rgb(std::sqrt(gpu::Turbulence(q, 0.02f * 0.02f, 0.5f, 8)))));
    write.Clamp(0.3f);
    EXPECT_TRUE(Near(Evaluate(program, At(p)),
                     Rgb(std::min(0.3f, std::sqrt(gpu::Turbulence(q, 0.0f, 0.5f, 8))))));
    reset();
    write.Solid(gpu::kTextureFbm, texture_from_world, 0.5f, 8);
    write.Clamp(1e30f);
    EXPECT_TRUE(
        Near(Evaluate(program, At(p)), Rgb(std::max(0.0f, gpu::FractalNoise(q, 0.0f, 0.5f, 8)))));
    // A 3D checkerboard.
    reset();
    write.Constant(Rgb(1.0f));
    write.Constant(Rgb(0.0f));
    write.Solid(gpu::kTextureCheckerboard3D, Transform{});
    EXPECT_TRUE(Near(Evaluate(program, At({0.5f, 0.5f, 0.5f})), Rgb(1.0f)));
    EXPECT_TRUE(Near(Evaluate(program, At({1.5f, 0.5f, 0.5f})), Rgb(0.0f)));
    EXPECT_TRUE(Near(Evaluate(program, At({1.5f, -0.5f, 0.5f})), Rgb(1.0f)));
}

TEST(ProceduralTextureTest, BrokenProgramsAreRefused) {
    const std::vector<std::shared_ptr<const Texture>> textures = {
        std::make_shared<const Texture>(Texture{1, 1, {Rgb(0.5f)}})};
    const auto check = [&](const std::vector<gpu::vec4>& program) {
        return CheckTextureProgram(program, textures);
    };
    std::vector<gpu::vec4> program;
    TextureProgramWriter write(&program);
    const double identity[6] = {1, 0, 0, 0, 1, 0};
    write.Image(0, identity);
    EXPECT_TRUE(check(program).ok()) << check(program);
    program.pop_back();
    EXPECT_FALSE(check(program).ok()) << "truncated";
    program.clear();
    write.Image(1, identity);
    EXPECT_FALSE(check(program).ok()) << "no texture 1";
    program.clear();
    write.Constant(Rgb(1.0f));
    write.Combine(gpu::kTextureMultiply);
    EXPECT_FALSE(check(program).ok()) << "an operand missing";
    program.clear();
    for (int i = 0; i < gpu::kTextureStackSize + 1; ++i) write.Constant(Rgb(1.0f));
    for (int i = 0; i < gpu::kTextureStackSize; ++i) write.Combine(gpu::kTextureMultiply);
    EXPECT_FALSE(check(program).ok()) << "too deep";
    program.clear();
    write.Constant(Rgb(1.0f));
    write.Constant(Rgb(1.0f));
    EXPECT_FALSE(check(program).ok()) << "two values left";
    program.clear();
    write.Solid(gpu::kTextureFbm, Transform{}, 0.5f, gpu::kMaxNoiseOctaves + 1);
    EXPECT_FALSE(check(program).ok()) << "too many octaves";
    program.clear();
    write.Constant(Rgb(1.0f));
    program[0].x = std::bit_cast<float>(gpu::kTextureOps);
    EXPECT_FALSE(check(program).ok()) << "an unknown instruction";
    program.clear();
    write.Constant(Rgb(std::nanf("")));
    EXPECT_FALSE(check(program).ok()) << "not finite";
}

}  // namespace
}  // namespace pf
