// Octahedral normals round-trip within a hundredth of a degree, across all octants.
#include "core/math/octahedral.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"

namespace pf {
namespace {

TEST(OctahedralTest, RoundTripsEveryDirectionClosely) {
    Rng rng(3);
    double worst_degrees = 0;
    for (int i = 0; i < 200000; ++i) {
        const Vec3 n = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
        // The angle from the cross product, in double: acos of a float dot product near 1
        // would measure float rounding, not the encoding.
        const Vec3d a(n), b(Normalize(Vec3d(DecodeOctahedral(EncodeOctahedral(n)))));
        const double degrees = std::atan2(Length(Cross(a, b)), Dot(a, b)) * 180 / M_PI;
        worst_degrees = std::max(worst_degrees, degrees);
    }
    EXPECT_LT(worst_degrees, 0.01);
    for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0),
                             Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
        const Vec3 decoded = Normalize(DecodeOctahedral(EncodeOctahedral(axis)));
        EXPECT_NEAR(Dot(decoded, axis), 1.0f, 1e-6f);
    }
}

}  // namespace
}  // namespace pf
