// Batch wire conversion with validation of everything a peer controls.
#include "worker/proto_convert.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace pf {
namespace {

absl::Status Invalid(const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat("batch result: ", what));
}

bool NonNegativeFinite(double v) { return std::isfinite(v) && v >= 0; }

}  // namespace

photonfarm::v1::BatchSpec ToProto(const BatchSpec& spec) {
    photonfarm::v1::BatchSpec out;
    out.set_index(spec.index);
    out.set_epoch(spec.epoch);
    out.set_photons(spec.photons);
    out.set_direct_begin(spec.direct_begin);
    out.set_direct_end(spec.direct_end);
    return out;
}

BatchSpec FromProto(const photonfarm::v1::BatchSpec& spec) {
    return {spec.index(), spec.epoch(), spec.photons(), spec.direct_begin(), spec.direct_end()};
}

photonfarm::v1::BatchResult ToProto(const BatchResult& result) {
    photonfarm::v1::BatchResult out;
    *out.mutable_spec() = ToProto(result.spec);
    photonfarm::v1::Tally* tally = out.mutable_tally();
    const size_t entries = result.tally.Size();
    tally->mutable_hit_point_delta()->Reserve(static_cast<int>(entries));
    tally->mutable_photons()->Reserve(static_cast<int>(entries));
    tally->mutable_flux()->Reserve(static_cast<int>(3 * entries));
    uint32_t previous = 0;
    for (size_t e = 0; e < entries; ++e) {
        tally->add_hit_point_delta(result.tally.hit_point[e] - previous);
        previous = result.tally.hit_point[e];
        tally->add_photons(result.tally.photons[e]);
        for (int c = 0; c < 3; ++c) tally->add_flux(result.tally.flux[e][c]);
    }
    out.mutable_direct()->Reserve(static_cast<int>(3 * result.direct.size()));
    for (const Rgb& direct : result.direct)
        for (int c = 0; c < 3; ++c) out.add_direct(direct[c]);
    out.set_photons_emitted(result.photons_emitted);
    out.set_segments_traced(result.segments_traced);
    return out;
}

absl::StatusOr<BatchResult> FromProto(const photonfarm::v1::BatchResult& message, uint32_t hit_point_count) {
    BatchResult result;
    result.spec = FromProto(message.spec());
    const BatchSpec& spec = result.spec;
    if (spec.direct_begin > spec.direct_end || spec.direct_end > hit_point_count)
        return Invalid(absl::StrCat("direct slice [", spec.direct_begin, ", ", spec.direct_end,
                                    ") lies outside the ", hit_point_count, " hit points"));
    const photonfarm::v1::Tally& tally = message.tally();
    const int entries = tally.hit_point_delta_size();
    if (tally.photons_size() != entries || tally.flux_size() != 3 * entries)
        return Invalid(absl::StrCat("tally sizes disagree: ", entries, " hit points, ", tally.photons_size(),
                                    " counts, ", tally.flux_size(), " flux values"));
    if (static_cast<uint64_t>(entries) > hit_point_count)
        return Invalid(absl::StrCat("tally has ", entries, " entries for ", hit_point_count, " hit points"));
    result.tally.hit_point.resize(entries);
    result.tally.photons.resize(entries);
    result.tally.flux.resize(entries);
    uint64_t hit_point = 0;
    for (int e = 0; e < entries; ++e) {
        const uint32_t delta = tally.hit_point_delta(e);
        if (e > 0 && delta == 0) return Invalid(absl::StrCat("tally entry ", e, " repeats or is out of order"));
        hit_point += delta;
        if (hit_point >= hit_point_count)
            return Invalid(absl::StrCat("tally entry ", e, " names hit point ", hit_point, " of ", hit_point_count));
        if (tally.photons(e) == 0) return Invalid(absl::StrCat("tally entry ", e, " has no photons"));
        const Rgb flux(tally.flux(3 * e), tally.flux(3 * e + 1), tally.flux(3 * e + 2));
        if (!NonNegativeFinite(flux.x) || !NonNegativeFinite(flux.y) || !NonNegativeFinite(flux.z))
            return Invalid(absl::StrCat("tally entry ", e, " has negative, NaN or Inf flux"));
        result.tally.hit_point[e] = static_cast<uint32_t>(hit_point);
        result.tally.photons[e] = tally.photons(e);
        result.tally.flux[e] = flux;
    }
    const uint32_t slice = spec.direct_end - spec.direct_begin;
    if (static_cast<uint64_t>(message.direct_size()) != 3ull * slice)
        return Invalid(absl::StrCat("direct has ", message.direct_size(), " values for a slice of ", slice));
    result.direct.resize(slice);
    for (uint32_t i = 0; i < slice; ++i) {
        const Rgb direct(message.direct(3 * i), message.direct(3 * i + 1), message.direct(3 * i + 2));
        if (!NonNegativeFinite(direct.x) || !NonNegativeFinite(direct.y) || !NonNegativeFinite(direct.z))
            return Invalid(absl::StrCat("direct sample ", i, " is negative, NaN or Inf"));
        result.direct[i] = direct;
    }
    if (message.photons_emitted() != spec.photons)
        return Invalid(absl::StrCat("emitted ", message.photons_emitted(), " photons for a batch of ", spec.photons));
    result.photons_emitted = message.photons_emitted();
    result.segments_traced = message.segments_traced();
    return result;
}

}  // namespace pf
