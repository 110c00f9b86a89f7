// One switch per enum and direction; see enums.h.
#include "wire/enums.h"

#include "absl/strings/str_cat.h"

namespace pf {
namespace v1 = photonfarm::v1;
namespace {

absl::Status Unknown(const char* field, int value) {
    return absl::InvalidArgumentError(absl::StrCat(field, " ", value, " is not a known value"));
}

}  // namespace

v1::Integrator ToProto(Integrator integrator) {
    switch (integrator) {
        case Integrator::kPpm:
            return v1::INTEGRATOR_PPM;
        case Integrator::kSppm:
            return v1::INTEGRATOR_SPPM;
        case Integrator::kPm:
            return v1::INTEGRATOR_PM;
        case Integrator::kPath:
            return v1::INTEGRATOR_PATH;
        case Integrator::kRpm:
            return v1::INTEGRATOR_RPM;
    }
    return v1::INTEGRATOR_UNSPECIFIED;
}

v1::PhotonTracing ToProto(PhotonTracing tracing) {
    switch (tracing) {
        case PhotonTracing::kAuto:
            return v1::PHOTON_TRACING_UNSPECIFIED;
        case PhotonTracing::kUniform:
            return v1::PHOTON_TRACING_UNIFORM;
        case PhotonTracing::kAdaptive:
            return v1::PHOTON_TRACING_ADAPTIVE;
    }
    return v1::PHOTON_TRACING_UNSPECIFIED;
}

v1::PhotonIndex ToProto(PhotonIndex index) {
    switch (index) {
        case PhotonIndex::kKdTree:
            return v1::PHOTON_INDEX_KDTREE;
        case PhotonIndex::kGrid:
            return v1::PHOTON_INDEX_GRID;
    }
    return v1::PHOTON_INDEX_UNSPECIFIED;
}

v1::DensityFilter ToProto(DensityFilter filter) {
    switch (filter) {
        case DensityFilter::kBox:
            return v1::DENSITY_FILTER_BOX;
        case DensityFilter::kCone:
            return v1::DENSITY_FILTER_CONE;
        case DensityFilter::kGaussian:
            return v1::DENSITY_FILTER_GAUSSIAN;
    }
    return v1::DENSITY_FILTER_UNSPECIFIED;
}

v1::JobState ToProto(JobState state) {
    switch (state) {
        case JobState::kRunning:
            return v1::JOB_STATE_RUNNING;
        case JobState::kDone:
            return v1::JOB_STATE_DONE;
        case JobState::kCancelled:
            return v1::JOB_STATE_CANCELLED;
        case JobState::kFailed:
            return v1::JOB_STATE_FAILED;
    }
    return v1::JOB_STATE_UNSPECIFIED;
}

v1::TallyVerdict ToProto(TallyVerdict verdict) {
    switch (verdict) {
        case TallyVerdict::kAccepted:
            return v1::TALLY_VERDICT_ACCEPTED;
        case TallyVerdict::kDuplicate:
            return v1::TALLY_VERDICT_DUPLICATE;
        case TallyVerdict::kStale:
            return v1::TALLY_VERDICT_STALE;
        case TallyVerdict::kJobGone:
            return v1::TALLY_VERDICT_JOB_GONE;
        case TallyVerdict::kNotLeased:
            return v1::TALLY_VERDICT_NOT_LEASED;
    }
    return v1::TALLY_VERDICT_UNSPECIFIED;
}

absl::StatusOr<Integrator> IntegratorFromProto(int integrator, const char* field) {
    switch (integrator) {
        case v1::INTEGRATOR_UNSPECIFIED:
            return JobSpec{}.integrator;
        case v1::INTEGRATOR_PPM:
            return Integrator::kPpm;
        case v1::INTEGRATOR_SPPM:
            return Integrator::kSppm;
        case v1::INTEGRATOR_PM:
            return Integrator::kPm;
        case v1::INTEGRATOR_PATH:
            return Integrator::kPath;
        case v1::INTEGRATOR_RPM:
            return Integrator::kRpm;
        default:
            return Unknown(field, integrator);
    }
}

absl::StatusOr<PhotonTracing> PhotonTracingFromProto(int tracing, const char* field) {
    switch (tracing) {
        case v1::PHOTON_TRACING_UNSPECIFIED:
            return PhotonTracing::kAuto;
        case v1::PHOTON_TRACING_UNIFORM:
            return PhotonTracing::kUniform;
        case v1::PHOTON_TRACING_ADAPTIVE:
            return PhotonTracing::kAdaptive;
        default:
            return Unknown(field, tracing);
    }
}

absl::StatusOr<PhotonIndex> PhotonIndexFromProto(int index, const char* field) {
    switch (index) {
        case v1::PHOTON_INDEX_UNSPECIFIED:
            return PhotonMapSettings{}.index;
        case v1::PHOTON_INDEX_KDTREE:
            return PhotonIndex::kKdTree;
        case v1::PHOTON_INDEX_GRID:
            return PhotonIndex::kGrid;
        default:
            return Unknown(field, index);
    }
}

absl::StatusOr<DensityFilter> DensityFilterFromProto(int filter, const char* field) {
    switch (filter) {
        case v1::DENSITY_FILTER_UNSPECIFIED:
            return PhotonMapSettings{}.filter;
        case v1::DENSITY_FILTER_BOX:
            return DensityFilter::kBox;
        case v1::DENSITY_FILTER_CONE:
            return DensityFilter::kCone;
        case v1::DENSITY_FILTER_GAUSSIAN:
            return DensityFilter::kGaussian;
        default:
            return Unknown(field, filter);
    }
}

absl::StatusOr<JobState> JobStateFromProto(int state, const char* field) {
    switch (state) {
        case v1::JOB_STATE_RUNNING:
            return JobState::kRunning;
        case v1::JOB_STATE_DONE:
            return JobState::kDone;
        case v1::JOB_STATE_CANCELLED:
            return JobState::kCancelled;
        case v1::JOB_STATE_FAILED:
            return JobState::kFailed;
        default:
            return Unknown(field, state);
    }
}

absl::StatusOr<TallyVerdict> TallyVerdictFromProto(int verdict, const char* field) {
    switch (verdict) {
        case v1::TALLY_VERDICT_ACCEPTED:
            return TallyVerdict::kAccepted;
        case v1::TALLY_VERDICT_DUPLICATE:
            return TallyVerdict::kDuplicate;
        case v1::TALLY_VERDICT_STALE:
            return TallyVerdict::kStale;
        case v1::TALLY_VERDICT_JOB_GONE:
            return TallyVerdict::kJobGone;
        case v1::TALLY_VERDICT_NOT_LEASED:
            return TallyVerdict::kNotLeased;
        default:
            return Unknown(field, verdict);
    }
}

}  // namespace pf
