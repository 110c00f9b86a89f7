// Batch results survive the wire bit for bit, and hostile messages are refused.
#include "wire/proto_convert.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pf {
namespace {

BatchResult Sample() {
    BatchResult result;
    result.spec = {17, 2, 1000, 4, 7};
    result.tally.hit_point = {0, 3, 4, 9};
    result.tally.photons = {1, 5, 2, 7};
    result.tally.inner_photons = {0, 3, 2, 4};
    result.tally.flux = {Rgb(0.1f, 0.2f, 0.3f), Rgb(1e-30f, 1e30f, 0.0f), Rgb(3.0f),
                         Rgb(std::nextafter(1.0f, 2.0f))};
    result.samples = {Rgb(0.5f), Rgb(1.0f, 2.0f, 3.0f), Rgb(0.0f)};
    result.photons_emitted = 1000;
    result.segments_traced = 4321;
    return result;
}

TEST(ProtoConvertTest, RoundTripIsBitExact) {
    const BatchResult original = Sample();
    const std::string wire = ToProto(original).SerializeAsString();
    photonfarm::v1::BatchResult parsed;
    ASSERT_TRUE(parsed.ParseFromString(wire));
    const absl::StatusOr<BatchResult> decoded = FromProto(parsed, 10, 10);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_EQ(decoded->spec.index, original.spec.index);
    EXPECT_EQ(decoded->spec.sample_end, original.spec.sample_end);
    EXPECT_EQ(decoded->tally.hit_point, original.tally.hit_point);
    EXPECT_EQ(decoded->tally.photons, original.tally.photons);
    EXPECT_EQ(decoded->tally.inner_photons, original.tally.inner_photons);
    EXPECT_EQ(decoded->tally.flux, original.tally.flux);
    EXPECT_EQ(decoded->samples, original.samples);
    EXPECT_EQ(decoded->segments_traced, original.segments_traced);
}

TEST(ProtoConvertTest, JobSettingsWithAnEnvironmentRoundTrip) {
    JobSpec spec;
    spec.epoch_budget = 3;
    spec.environment.file = "photonfarm-environment.exr";
    spec.environment.scale = 2.5;
    spec.environment.rotate_degrees = -45;
    absl::StatusOr<JobSpec> decoded = FromProto(ToProto(spec));
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_EQ(decoded->environment, spec.environment);
    spec.environment = {};
    spec.environment.color = Rgb(0.1f, 0.2f, 0.3f);
    decoded = FromProto(ToProto(spec));
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_EQ(decoded->environment, spec.environment);
    JobSpec plain;
    plain.epoch_budget = 3;
    EXPECT_FALSE(FromProto(ToProto(plain))->environment.Given());
    // Hostile values are refused naming the field.
    const auto refused = [&](auto mutate, const std::string& field) {
        photonfarm::v1::JobSettings message = ToProto(spec);
        mutate(*message.mutable_environment());
        const absl::StatusOr<JobSpec> result = FromProto(message);
        ASSERT_FALSE(result.ok()) << field;
        EXPECT_NE(result.status().message().find(field), std::string::npos) << result.status();
    };
    refused([](auto& e) { e.add_color(1.0f); }, "settings.environment.color");
    refused([](auto& e) { e.set_color(1, -1.0f); }, "settings.environment.color");
    refused([](auto& e) { e.set_color(0, std::nanf("")); }, "settings.environment.color");
    refused([](auto& e) { e.set_scale(-1); }, "settings.environment.scale");
    refused([](auto& e) { e.set_rotate_degrees(1e300); }, "settings.environment.rotate_degrees");
    refused([](auto& e) { e.set_file("sky.exr"); }, "settings.environment.color");
}

TEST(ProtoConvertTest, MaximumDepthRoundTripsAndIsBounded) {
    JobSpec spec;
    spec.epoch_budget = 3;
    spec.max_depth = 5;
    EXPECT_EQ(FromProto(ToProto(spec))->max_depth, 5);
    photonfarm::v1::JobSettings message = ToProto(spec);
    message.set_max_depth(UINT32_MAX);
    const absl::StatusOr<JobSpec> refused = FromProto(message);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.status().message(), "settings.max_depth 4294967295 is out of range");
}

TEST(ProtoConvertTest, PhotonTracingRoundTripsAndAppliesToThePhotonMappersOnly) {
    JobSpec spec;
    spec.epoch_budget = 3;
    spec.photon_tracing = PhotonTracing::kAdaptive;
    EXPECT_EQ(FromProto(ToProto(spec))->photon_tracing, PhotonTracing::kAdaptive);
    spec.integrator = Integrator::kPath;
    const absl::StatusOr<JobSpec> refused = FromProto(ToProto(spec));
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.status().message(),
              "settings.photon_tracing applies to ppm, sppm and rpm, whose photons gather at "
              "hit points, not to the path integrator");
}

TEST(ProtoConvertTest, HostileResultsAreRefused) {
    const auto refused = [](auto mutate) {
        photonfarm::v1::BatchResult message = ToProto(Sample());
        mutate(message);
        return !FromProto(message, 10, 10).ok();
    };
    EXPECT_TRUE(
        refused([](auto& m) { m.mutable_tally()->set_hit_point_delta(3, 100); }));  // out of range
    EXPECT_TRUE(
        refused([](auto& m) { m.mutable_tally()->set_hit_point_delta(2, 0); }));  // repeated
    EXPECT_TRUE(refused(
        [](auto& m) { m.mutable_tally()->set_flux(4, std::numeric_limits<double>::quiet_NaN()); }));
    EXPECT_TRUE(refused([](auto& m) { m.mutable_tally()->set_flux(0, -1.0); }));
    EXPECT_TRUE(refused([](auto& m) { m.mutable_tally()->add_photons(1); }));  // sizes disagree
    EXPECT_TRUE(refused([](auto& m) { m.mutable_tally()->set_photons(0, 0); }));
    EXPECT_TRUE(
        refused([](auto& m) { m.mutable_tally()->add_inner_photons(1); }));  // sizes disagree
    EXPECT_TRUE(
        refused([](auto& m) { m.mutable_tally()->set_inner_photons(1, 6); }));  // more than photons
    EXPECT_TRUE(refused([](auto& m) { m.set_samples(2, std::numeric_limits<float>::infinity()); }));
    EXPECT_TRUE(refused([](auto& m) { m.mutable_spec()->set_sample_end(11); }));  // slice beyond
    EXPECT_TRUE(refused([](auto& m) { m.set_photons_emitted(999); }));
    EXPECT_FALSE(refused([](auto&) {}));
}

}  // namespace
}  // namespace pf
