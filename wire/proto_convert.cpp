// Batch wire conversion with validation of everything a peer controls.
#include "wire/proto_convert.h"

#include <cmath>
#include <limits>
#include <span>
#include <tuple>
#include <vector>

#include "absl/strings/str_cat.h"
#include "wire/blob_codec.h"

namespace pf {
namespace {

absl::Status Invalid(const std::string& what) {
    return absl::InvalidArgumentError(absl::StrCat("batch result: ", what));
}

bool NonNegativeFinite(double v) { return std::isfinite(v) && v >= 0; }

void AddColours(std::span<const Rgb> colours, google::protobuf::RepeatedField<float>* out) {
    out->Reserve(static_cast<int>(3 * colours.size()));
    for (const Rgb& colour : colours)
        for (int c = 0; c < 3; ++c) out->Add(colour[c]);
}

// `values` read three at a time as colours, each non-negative and finite; `what` names them.
absl::StatusOr<std::vector<Rgb>> Colours(const google::protobuf::RepeatedField<float>& values,
                                         const char* what) {
    if (values.size() % 3 != 0)
        return Invalid(absl::StrCat(what, " has ", values.size(), " values, not three a colour"));
    std::vector<Rgb> colours(static_cast<size_t>(values.size() / 3));
    for (size_t i = 0; i < colours.size(); ++i) {
        const Rgb colour(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
        if (!NonNegativeFinite(colour.x) || !NonNegativeFinite(colour.y) ||
            !NonNegativeFinite(colour.z))
            return Invalid(absl::StrCat(what, " ", i, " is negative, NaN or Inf"));
        colours[i] = colour;
    }
    return colours;
}

}  // namespace

photonfarm::v1::BatchSpec ToProto(const BatchSpec& spec) {
    photonfarm::v1::BatchSpec out;
    out.set_index(spec.index);
    out.set_epoch(spec.epoch);
    out.set_photons(spec.photons);
    out.set_sample_begin(spec.sample_begin);
    out.set_sample_end(spec.sample_end);
    return out;
}

BatchSpec FromProto(const photonfarm::v1::BatchSpec& spec) {
    return {spec.index(), spec.epoch(), spec.photons(), spec.sample_begin(), spec.sample_end()};
}

photonfarm::v1::BatchResult ToProto(const BatchResult& result) {
    photonfarm::v1::BatchResult out;
    *out.mutable_spec() = ToProto(result.spec);
    photonfarm::v1::Tally* tally = out.mutable_tally();
    const size_t entries = result.tally.Size();
    tally->mutable_hit_point_delta()->Reserve(static_cast<int>(entries));
    tally->mutable_photons()->Reserve(static_cast<int>(entries));
    tally->mutable_inner_photons()->Reserve(static_cast<int>(entries));
    tally->mutable_flux()->Reserve(static_cast<int>(3 * entries));
    uint32_t previous = 0;
    for (size_t e = 0; e < entries; ++e) {
        tally->add_hit_point_delta(result.tally.hit_point[e] - previous);
        previous = result.tally.hit_point[e];
        tally->add_photons(result.tally.photons[e]);
        tally->add_inner_photons(result.tally.inner_photons[e]);
        for (int c = 0; c < 3; ++c) tally->add_flux(result.tally.flux[e][c]);
    }
    AddColours(result.samples, out.mutable_samples());
    AddColours(result.emission, out.mutable_emission());
    AddColours(result.coverage, out.mutable_coverage());
    out.set_photons_emitted(result.photons_emitted);
    out.set_segments_traced(result.segments_traced);
    out.set_nonfinite_discarded(result.nonfinite_discarded);
    return out;
}

absl::StatusOr<BatchResult> FromProto(const photonfarm::v1::BatchResult& message,
                                      uint32_t hit_point_count, uint32_t item_count) {
    BatchResult result;
    result.spec = FromProto(message.spec());
    const BatchSpec& spec = result.spec;
    if (spec.sample_begin > spec.sample_end || spec.sample_end > item_count)
        return Invalid(absl::StrCat("sample slice [", spec.sample_begin, ", ", spec.sample_end,
                                    ") lies outside the job's ", item_count, " items"));
    const photonfarm::v1::Tally& tally = message.tally();
    const int entries = tally.hit_point_delta_size();
    if (tally.photons_size() != entries || tally.inner_photons_size() != entries ||
        tally.flux_size() != 3 * entries)
        return Invalid(absl::StrCat("tally sizes disagree: ", entries, " hit points, ",
                                    tally.photons_size(), " counts, ", tally.inner_photons_size(),
                                    " inner counts, ", tally.flux_size(), " flux values"));
    if (static_cast<uint64_t>(entries) > hit_point_count)
        return Invalid(
            absl::StrCat("tally has ", entries, " entries for ", hit_point_count, " hit points"));
    result.tally.hit_point.resize(entries);
    result.tally.photons.resize(entries);
    result.tally.inner_photons.resize(entries);
    result.tally.flux.resize(entries);
    uint64_t hit_point = 0;
    for (int e = 0; e < entries; ++e) {
        const uint32_t delta = tally.hit_point_delta(e);
        if (e > 0 && delta == 0)
            return Invalid(absl::StrCat("tally entry ", e, " repeats or is out of order"));
        hit_point += delta;
        if (hit_point >= hit_point_count)
            return Invalid(absl::StrCat("tally entry ", e, " names hit point ", hit_point, " of ",
                                        hit_point_count));
        if (tally.photons(e) == 0)
            return Invalid(absl::StrCat("tally entry ", e, " has no photons"));
        if (tally.inner_photons(e) > tally.photons(e))
            return Invalid(absl::StrCat("tally entry ", e, " has more inner photons than photons"));
        const Rgb flux(tally.flux(3 * e), tally.flux(3 * e + 1), tally.flux(3 * e + 2));
        if (!NonNegativeFinite(flux.x) || !NonNegativeFinite(flux.y) || !NonNegativeFinite(flux.z))
            return Invalid(absl::StrCat("tally entry ", e, " has negative, NaN or Inf flux"));
        result.tally.hit_point[e] = static_cast<uint32_t>(hit_point);
        result.tally.photons[e] = tally.photons(e);
        result.tally.inner_photons[e] = tally.inner_photons(e);
        result.tally.flux[e] = flux;
    }
    const uint32_t slice = spec.sample_end - spec.sample_begin;
    if (static_cast<uint64_t>(message.samples_size()) != 3ull * slice)
        return Invalid(
            absl::StrCat("samples has ", message.samples_size(), " values for a slice of ", slice));
    // The direct samples, then ppm's share of the emission pass, whose sizes the job checks
    // (Estimate::EmissionShape).
    for (auto [field, what, out] :
         {std::tuple(&message.samples(), "sample", &result.samples),
          std::tuple(&message.emission(), "emission", &result.emission),
          std::tuple(&message.coverage(), "coverage", &result.coverage)}) {
        absl::StatusOr<std::vector<Rgb>> colours = Colours(*field, what);
        if (!colours.ok()) return colours.status();
        *out = std::move(*colours);
    }
    if (message.photons_emitted() != spec.photons)
        return Invalid(absl::StrCat("emitted ", message.photons_emitted(),
                                    " photons for a batch of ", spec.photons));
    result.photons_emitted = message.photons_emitted();
    result.segments_traced = message.segments_traced();
    result.nonfinite_discarded = message.nonfinite_discarded();
    return result;
}

photonfarm::v1::SceneBundle ToProto(const SceneBundle& bundle) {
    photonfarm::v1::SceneBundle out;
    out.set_main_file(bundle.main_file);
    for (const auto& [path, content] : bundle.files) {
        photonfarm::v1::BundleFile* file = out.add_files();
        file->set_path(path);
        file->set_content(content);
    }
    return out;
}

absl::StatusOr<SceneBundle> FromProto(const photonfarm::v1::SceneBundle& message) {
    SceneBundle bundle;
    bundle.main_file = message.main_file();
    for (const photonfarm::v1::BundleFile& file : message.files()) {
        if (absl::Status status = CheckBundlePath(file.path()); !status.ok())
            return absl::InvalidArgumentError(absl::StrCat("scene.files: ", status.message()));
        if (!bundle.files.emplace(file.path(), file.content()).second)
            return absl::InvalidArgumentError(
                absl::StrCat("scene.files: '", file.path(), "' given twice"));
    }
    if (absl::Status status = CheckSceneBundle(bundle); !status.ok())
        return absl::InvalidArgumentError(absl::StrCat("scene: ", status.message()));
    return bundle;
}

photonfarm::v1::JobSettings ToProto(const JobSpec& spec) {
    photonfarm::v1::JobSettings out;
    out.set_width(spec.width);
    out.set_height(spec.height);
    out.set_samples_per_pixel(spec.samples_per_pixel);
    out.set_photon_budget(spec.photon_budget);
    out.set_seconds_budget(spec.seconds_budget);
    out.set_target_error(spec.target_error);
    out.set_alpha(spec.alpha);
    out.set_initial_radius(spec.initial_radius);
    out.set_seed(spec.seed);
    out.set_photon_stream(spec.photon_stream);
    out.set_photons_per_batch(spec.layout.photons_per_batch);
    out.set_batches_per_epoch(spec.layout.batches_per_epoch);
    out.set_first_epoch_photons(spec.layout.first_epoch_photons);
    out.set_photon_tracing(ToProto(spec.photon_tracing));
    out.set_integrator(ToProto(spec.integrator));
    out.set_epoch_budget(spec.epoch_budget);
    out.set_until_cancelled(spec.until_cancelled);
    out.set_camera(spec.camera);
    out.set_max_depth(static_cast<uint32_t>(spec.max_depth));
    if (spec.environment.Given()) {
        const EnvironmentSettings& environment = spec.environment;
        photonfarm::v1::EnvironmentSettings* out_environment = out.mutable_environment();
        out_environment->set_file(environment.file);
        if (environment.color)
            for (int c = 0; c < 3; ++c) out_environment->add_color((*environment.color)[c]);
        out_environment->set_scale(environment.scale);
        out_environment->set_rotate_degrees(environment.rotate_degrees);
    }
    if (spec.integrator == Integrator::kPm || spec.integrator == Integrator::kRpm) {
        const PhotonMapSettings& maps = spec.photon_map;
        photonfarm::v1::PhotonMapSettings* out_maps = out.mutable_photon_map();
        out_maps->set_global_photons(maps.global_photons);
        out_maps->set_caustic_photons(maps.caustic_photons);
        out_maps->set_nearest(maps.nearest);
        out_maps->set_max_radius(maps.max_radius);
        out_maps->set_filter(ToProto(maps.filter));
        out_maps->set_final_gather(maps.final_gather);
        out_maps->set_index(ToProto(maps.index));
    }
    return out;
}

absl::StatusOr<JobSpec> FromProto(const photonfarm::v1::JobSettings& settings) {
    JobSpec spec;
    auto too_large = [](const char* field, uint64_t value) {
        return absl::InvalidArgumentError(
            absl::StrCat("settings.", field, " ", value, " is out of range"));
    };
    if (settings.width() > 32768) return too_large("width", settings.width());
    if (settings.height() > 32768) return too_large("height", settings.height());
    if (settings.samples_per_pixel() > 1024)
        return too_large("samples_per_pixel", settings.samples_per_pixel());
    spec.width = static_cast<int>(settings.width());
    spec.height = static_cast<int>(settings.height());
    if (settings.samples_per_pixel() != 0)
        spec.samples_per_pixel = static_cast<int>(settings.samples_per_pixel());
    spec.photon_budget = settings.photon_budget();
    spec.seconds_budget = settings.seconds_budget();
    spec.alpha = settings.alpha();
    spec.initial_radius = settings.initial_radius();
    spec.seed = settings.seed();
    spec.photon_stream = settings.photon_stream();
    if (settings.photons_per_batch() != 0)
        spec.layout.photons_per_batch = settings.photons_per_batch();
    if (settings.batches_per_epoch() != 0)
        spec.layout.batches_per_epoch = settings.batches_per_epoch();
    spec.layout.first_epoch_photons = settings.first_epoch_photons();
    spec.target_error = settings.target_error();
    spec.epoch_budget = settings.epoch_budget();
    spec.until_cancelled = settings.until_cancelled();
    spec.camera = settings.camera();
    if (settings.max_depth() > static_cast<uint32_t>(kMaxDepthSetting))
        return too_large("max_depth", settings.max_depth());
    spec.max_depth = static_cast<int>(settings.max_depth());
    if (settings.has_environment()) {
        const photonfarm::v1::EnvironmentSettings& in = settings.environment();
        if (in.file().size() > 4096) return too_large("environment.file length", in.file().size());
        spec.environment.file = in.file();
        if (in.color_size() != 0 && in.color_size() != 3)
            return absl::InvalidArgumentError(absl::StrCat(
                "settings.environment.color holds ", in.color_size(), " values, not 3 (R, G, B)"));
        if (in.color_size() == 3)
            spec.environment.color = Rgb(in.color(0), in.color(1), in.color(2));
        if (in.scale() != 0) spec.environment.scale = in.scale();
        spec.environment.rotate_degrees = in.rotate_degrees();
    }
    PhotonMapSettings& maps = spec.photon_map;
    const photonfarm::v1::PhotonMapSettings& in_maps = settings.photon_map();
    absl::StatusOr<Integrator> integrator =
        IntegratorFromProto(settings.integrator(), "settings.integrator");
    absl::StatusOr<DensityFilter> filter =
        DensityFilterFromProto(in_maps.filter(), "settings.photon_map.filter");
    absl::StatusOr<PhotonIndex> index =
        PhotonIndexFromProto(in_maps.index(), "settings.photon_map.index");
    absl::StatusOr<PhotonTracing> tracing =
        PhotonTracingFromProto(settings.photon_tracing(), "settings.photon_tracing");
    if (!integrator.ok()) return integrator.status();
    if (!tracing.ok()) return tracing.status();
    if (!filter.ok()) return filter.status();
    if (!index.ok()) return index.status();
    spec.integrator = *integrator;
    spec.photon_tracing = *tracing;
    maps.filter = *filter;
    maps.index = *index;
    if (in_maps.global_photons() != 0 || in_maps.caustic_photons() != 0) {
        maps.global_photons = in_maps.global_photons();
        maps.caustic_photons = in_maps.caustic_photons();
    }
    if (in_maps.nearest() != 0) maps.nearest = in_maps.nearest();
    maps.max_radius = in_maps.max_radius();
    maps.final_gather = in_maps.final_gather();
    if (absl::Status status = CheckJobSpec(spec, SettingNames::kFields); !status.ok())
        return status;
    return spec;
}

photonfarm::v1::JobStatus ToProto(const JobProgress& progress) {
    photonfarm::v1::JobStatus status;
    status.set_job_id(progress.job_id);
    status.set_name(progress.name);
    status.set_state(ToProto(progress.state));
    status.set_epochs(progress.epochs);
    status.set_photons(progress.photons);
    status.set_elapsed_seconds(progress.elapsed_seconds);
    status.set_photons_per_second(progress.photons_per_second);
    status.set_workers_active(progress.workers_active);
    status.set_priority(progress.priority);
    status.set_hit_points(progress.hit_points);
    status.set_budget_fraction(progress.budget_fraction);
    if (progress.estimated_error) status.set_estimated_error(*progress.estimated_error);
    if (progress.measured_error)
        *status.mutable_reference_error() = ToProto(*progress.measured_error);
    status.set_nonfinite_discarded(progress.nonfinite_discarded);
    status.set_scene_features(progress.scene_features);
    status.set_integrator(ToProto(progress.integrator));
    status.set_camera_samples(progress.camera_samples);
    status.set_owner(progress.owner);
    status.set_message(progress.message);
    for (const std::string& warning : progress.warnings) status.add_warnings(warning);
    return status;
}

photonfarm::v1::Image ToProto(const Image& image) {
    photonfarm::v1::Image out;
    out.set_width(image.width);
    out.set_height(image.height);
    out.set_rgb_f32_zstd(EncodeImagePixels(image));
    return out;
}

absl::StatusOr<Image> FromProto(const photonfarm::v1::Image& image) {
    if (image.width() > std::numeric_limits<int>::max() ||
        image.height() > std::numeric_limits<int>::max())
        return absl::InvalidArgumentError("image: size out of range");
    return DecodeImagePixels(image.rgb_f32_zstd(), static_cast<int>(image.width()),
                             static_cast<int>(image.height()));
}

photonfarm::v1::ReferenceError ToProto(const ImageDifference& difference) {
    photonfarm::v1::ReferenceError out;
    out.set_rmse(difference.rmse);
    out.set_rel_mse(difference.rel_mse);
    out.set_nonfinite_pixels(difference.nonfinite_pixels);
    return out;
}

ImageDifference FromProto(const photonfarm::v1::ReferenceError& error) {
    ImageDifference difference;
    difference.rmse = error.rmse();
    difference.rel_mse = error.rel_mse();
    difference.nonfinite_pixels = error.nonfinite_pixels();
    return difference;
}

photonfarm::v1::ConvergencePoint ToProto(const ConvergencePoint& point) {
    photonfarm::v1::ConvergencePoint out;
    out.set_seconds(point.seconds);
    out.set_epochs(point.epochs);
    out.set_photons(point.photons);
    out.set_camera_samples(point.camera_samples);
    if (point.estimated) {
        out.set_estimated_rmse(point.estimated->rmse);
        out.set_estimated_rel_mse(point.estimated->rel_mse);
        out.set_estimated_bias_rmse(point.estimated->bias_rmse);
    }
    if (point.measured) *out.mutable_reference_error() = ToProto(*point.measured);
    return out;
}

ConvergencePoint FromProto(const photonfarm::v1::ConvergencePoint& point, uint64_t pixels) {
    ConvergencePoint out;
    out.seconds = point.seconds();
    out.epochs = point.epochs();
    out.photons = point.photons();
    out.camera_samples = point.camera_samples();
    if (point.has_estimated_rmse() && point.has_estimated_rel_mse())
        out.estimated = ErrorEstimate{true, point.estimated_rmse(), point.estimated_rel_mse(),
                                      point.estimated_bias_rmse()};
    if (point.has_reference_error()) out.measured = FromProto(point.reference_error());
    out.pixels = pixels;
    return out;
}

}  // namespace pf
