// Every enum that crosses the wire, every value, both ways: core -> wire -> core is the
// identity, every wire value but UNSPECIFIED comes from exactly one core value, UNSPECIFIED
// in settings is the setting's default, and values the wire does not define are refused
// naming the field.
#include "wire/enums.h"

#include <gtest/gtest.h>

#include <set>

namespace pf {
namespace {

namespace v1 = photonfarm::v1;

// Checks the round trip of `values` and that their wire values cover every named wire value
// of `descriptor` but UNSPECIFIED (0), once each.
template <typename Core, typename ToCore>
void ExpectBijection(const std::vector<Core>& values,
                     const google::protobuf::EnumDescriptor* descriptor, ToCore to_core) {
    std::set<int> seen;
    for (Core value : values) {
        const int wire = static_cast<int>(ToProto(value));
        EXPECT_NE(wire, 0) << descriptor->name() << ": a core value maps to UNSPECIFIED";
        EXPECT_TRUE(seen.insert(wire).second) << descriptor->name() << " " << wire << " twice";
        const absl::StatusOr<Core> back = to_core(wire, "field");
        ASSERT_TRUE(back.ok()) << back.status();
        EXPECT_EQ(*back, value) << descriptor->name() << " " << wire;
    }
    for (int i = 0; i < descriptor->value_count(); ++i) {
        const int number = descriptor->value(i)->number();
        if (number != 0) {
            EXPECT_TRUE(seen.count(number)) << descriptor->value(i)->name() << " has no core value";
        }
    }
    for (int unknown : {-1, descriptor->value_count(), 1000}) {
        const absl::StatusOr<Core> refused = to_core(unknown, "settings.field");
        EXPECT_TRUE(absl::IsInvalidArgument(refused.status())) << unknown;
        EXPECT_NE(refused.status().message().find("settings.field"), std::string::npos)
            << refused.status();
    }
}

TEST(WireEnumsTest, IntegratorsMapOneToOneAndUnspecifiedIsTheDefault) {
    ExpectBijection<Integrator>(
        {Integrator::kPpm, Integrator::kSppm, Integrator::kPm, Integrator::kRpm, Integrator::kPath},
        v1::Integrator_descriptor(), IntegratorFromProto);
    EXPECT_EQ(*IntegratorFromProto(v1::INTEGRATOR_UNSPECIFIED, "f"), JobSpec{}.integrator);
}

TEST(WireEnumsTest, PhotonMapEnumsMapOneToOneAndUnspecifiedIsTheDefault) {
    ExpectBijection<PhotonIndex>({PhotonIndex::kKdTree, PhotonIndex::kGrid},
                                 v1::PhotonIndex_descriptor(), PhotonIndexFromProto);
    ExpectBijection<DensityFilter>(
        {DensityFilter::kBox, DensityFilter::kCone, DensityFilter::kGaussian},
        v1::DensityFilter_descriptor(), DensityFilterFromProto);
    EXPECT_EQ(*PhotonIndexFromProto(v1::PHOTON_INDEX_UNSPECIFIED, "f"), PhotonMapSettings{}.index);
    EXPECT_EQ(*DensityFilterFromProto(v1::DENSITY_FILTER_UNSPECIFIED, "f"),
              PhotonMapSettings{}.filter);
}

TEST(WireEnumsTest, PhotonTracingMapsOneToOneAndUnspecifiedIsAuto) {
    ExpectBijection<PhotonTracing>({PhotonTracing::kUniform, PhotonTracing::kAdaptive},
                                   v1::PhotonTracing_descriptor(), PhotonTracingFromProto);
    EXPECT_EQ(ToProto(PhotonTracing::kAuto), v1::PHOTON_TRACING_UNSPECIFIED);
    EXPECT_EQ(*PhotonTracingFromProto(v1::PHOTON_TRACING_UNSPECIFIED, "f"),
              JobSpec{}.photon_tracing);
    EXPECT_EQ(JobSpec{}.photon_tracing, PhotonTracing::kAuto);
}

TEST(WireEnumsTest, StatesAndVerdictsMapOneToOneAndMustBeSpecified) {
    ExpectBijection<JobState>(
        {JobState::kRunning, JobState::kDone, JobState::kCancelled, JobState::kFailed},
        v1::JobState_descriptor(), JobStateFromProto);
    ExpectBijection<TallyVerdict>(
        {TallyVerdict::kAccepted, TallyVerdict::kDuplicate, TallyVerdict::kStale,
         TallyVerdict::kJobGone, TallyVerdict::kNotLeased},
        v1::TallyVerdict_descriptor(), TallyVerdictFromProto);
    EXPECT_FALSE(JobStateFromProto(v1::JOB_STATE_UNSPECIFIED, "state").ok());
    EXPECT_FALSE(TallyVerdictFromProto(v1::TALLY_VERDICT_UNSPECIFIED, "verdict").ok());
}

}  // namespace
}  // namespace pf
