// farm_load's jobs: each is a real ppm job whose first epoch is traced for real, here, once;
// its tallies are then replayed for every epoch by the simulated workers, so the coordinator
// decodes and folds real tallies while the harness spends no time tracing. The same replay
// through an in-process coordinator gives the job's reference image: the farm's final image
// must equal it bit for bit (nothing lost, nothing counted twice, whatever the load).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/film/image.h"
#include "core/scene/scene_bundle.h"
#include "photonfarm/v1/batch.pb.h"
#include "photonfarm/v1/jobs.pb.h"

namespace pf::load {

struct JobShape {
    uint32_t width = 64, height = 64;
    uint32_t photons_per_batch = 1u << 14;
    uint32_t batches_per_epoch = 64;
    uint64_t epochs = 8;
};

// A job's settings for `seed`: ppm, one hit point per pixel, every epoch full, a fixed alpha.
photonfarm::v1::JobSettings LoadJobSettings(const JobShape& shape, uint64_t seed);

struct RecordedJob {
    photonfarm::v1::JobSettings settings;
    // The first epoch's results by batch index within the epoch, as ReportTally carries them;
    // a replay sets the spec to the leased one.
    std::vector<photonfarm::v1::BatchResult> batches;
    Image reference;       // the final image of the job with every epoch replayed
    uint64_t photons = 0;  // the photons merged into it
    double record_seconds = 0;
};

// Runs `settings`' job on `bundle` in this process (a coordinator, a worker loop on the CPU
// backend with `threads` threads) with its first epoch traced and later ones replayed.
absl::StatusOr<RecordedJob> RecordJob(const SceneBundle& bundle,
                                      const photonfarm::v1::JobSettings& settings, int threads);

// The recorded result for leased batch `spec`, as a worker would report it.
photonfarm::v1::BatchResult ReplayedResult(const RecordedJob& job,
                                           const photonfarm::v1::BatchSpec& spec);

}  // namespace pf::load
