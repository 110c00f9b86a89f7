// The sheen layer (core/shared/sheen.h): its albedo tables agree with the lobe integrated
// numerically, between their nodes too. With PF_PRINT_SHEEN_TABLES set, the test prints the
// tables afresh, integrated finely, in core/shared/sheen_tables.h's form.
#include "core/shared/sheen.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <thread>
#include <vector>

namespace pf {
namespace {

// E(mu) for sheen roughness r: the integral of f_sheen cos over the hemisphere, by the midpoint
// rule in (cos, azimuth) on a steps x steps grid (the lobe is symmetric about the plane of wo).
double IntegrateAlbedo(double mu, double roughness, int steps) {
    const float alpha = gpu::SheenAlpha(static_cast<float>(roughness));
    const Vec3 wo(static_cast<float>(std::sqrt(1 - mu * mu)), 0, static_cast<float>(mu));
    double sum = 0;
    for (int i = 0; i < steps; ++i) {
        const double cos_i = (i + 0.5) / steps;
        const double sin_i = std::sqrt(1 - cos_i * cos_i);
        for (int j = 0; j < steps; ++j) {
            const double phi = std::numbers::pi * (j + 0.5) / steps;
            const Vec3 wi(static_cast<float>(sin_i * std::cos(phi)),
                          static_cast<float>(sin_i * std::sin(phi)), static_cast<float>(cos_i));
            sum += gpu::SheenBrdf(wo, wi, alpha) * cos_i;
        }
    }
    return sum * 2 * std::numbers::pi / (double(steps) * steps);
}

double NodeCosine(int column) {
    const double x = double(column) / (gpu::kSheenCosines - 1);
    return std::max(x * x, 1e-5);  // at mu = 0 itself the lobe is 0 / 0
}

double NodeRoughness(int row) {
    const double t = double(row) / (gpu::kSheenRoughnesses - 1);
    return gpu::kMinSheenRoughness + (1 - gpu::kMinSheenRoughness) * t * t;
}

// 2 integral E(mu) mu dmu, in x = sqrt(mu) (4 x^3 dx) by the midpoint rule.
double IntegrateAverage(double roughness, int cosines, int steps) {
    double sum = 0;
    for (int k = 0; k < cosines; ++k) {
        const double x = (k + 0.5) / cosines;
        sum += 4 * x * x * x * IntegrateAlbedo(x * x, roughness, steps);
    }
    return sum / cosines;
}

void PrintTables() {
    constexpr int kSteps = 700;
    const int rows = gpu::kSheenRoughnesses, columns = gpu::kSheenCosines;
    std::vector<double> albedo(rows * columns), average(rows);
    std::vector<std::thread> threads;
    const int workers = std::max(1u, std::thread::hardware_concurrency());
    for (int w = 0; w < workers; ++w)
        threads.emplace_back([&, w] {
            for (int row = w; row < rows; row += workers) {
                for (int column = 0; column < columns; ++column)
                    albedo[row * columns + column] =
                        IntegrateAlbedo(NodeCosine(column), NodeRoughness(row), kSteps);
                average[row] = IntegrateAverage(NodeRoughness(row), 64, kSteps / 2);
            }
        });
    for (std::thread& thread : threads) thread.join();
    albedo.insert(albedo.end(), average.begin(), average.end());  // kSheenTables' order
    std::printf("inline constexpr float kSheenTables[kSheenTableSize] = {\n");
    for (size_t i = 0; i < albedo.size(); ++i)
        std::printf("%.5ff%s", albedo[i],
                    i + 1 == albedo.size() ? "\n" : (i % 8 == 7 ? ",\n" : ", "));
    std::printf("};\n");
}

TEST(SheenTest, TablesMatchTheLobeIntegrated) {
    if (std::getenv("PF_PRINT_SHEEN_TABLES") != nullptr) PrintTables();
    // Halfway between nodes in both directions, where the interpolation is furthest from them:
    // within 1.5% (and 2e-3) above the first column's interval, mu above 0.001, where E
    // falls steeply at high roughness (5% off at mu = 3e-4, an angle light rarely meets).
    for (int row = 0; row + 1 < gpu::kSheenRoughnesses; row += 2) {
        for (int column = 1; column + 1 < gpu::kSheenCosines; column += 2) {
            const double r = (NodeRoughness(row) + NodeRoughness(row + 1)) / 2;
            const double x = (column + 0.5) / (gpu::kSheenCosines - 1);
            const double integrated = IntegrateAlbedo(x * x, r, 240);
            EXPECT_NEAR(gpu::SheenAlbedo(float(x * x), float(r)), integrated,
                        0.015 * integrated + 2e-3)
                << "roughness " << r << ", cosine " << x * x;
        }
    }
}

}  // namespace
}  // namespace pf
