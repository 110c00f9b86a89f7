// The Vulkan compute backend: the same batches as the CPU backend, for every integrator,
// traced by compute kernels on the chosen device (a GPU, or lavapipe). Per job: the scene's
// buffers and kernels specialised to its features (and to the job: pm's maps built on the host
// and uploaded). Photon integrators (ppm, sppm, rpm): per epoch, the radii uploaded and the
// hit-point grid rebuilt on the device (for sppm and rpm, the epoch's hit points traced on the
// CPU and uploaded first); per batch, photon and direct-light kernels, then the tally read back
// and made sparse. Pixel integrators (path, pm): per batch, the camera rays made on the host
// and a thread a pixel (pixel_trace.comp). Not thread-safe; one job at a time.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera/camera_pass.h"
#include "core/geometry/tracer.h"
#include "core/ppm/direct_light.h"
#include "core/ppm/epoch_passes.h"
#include "worker/backend.h"
#include "worker/backends/vulkan/buffer.h"
#include "worker/backends/vulkan/command_stream.h"
#include "worker/backends/vulkan/context.h"
#include "worker/backends/vulkan/gpu_scene.h"
#include "worker/backends/vulkan/kernels.h"
#include "worker/backends/vulkan/path_wavefront.h"
#include "worker/backends/vulkan/pixel_jobs.h"

namespace pf::vk {

// What a device can hold: its largest storage buffer and its device-local memory.
struct DeviceCapacity {
    std::string name;
    uint64_t max_buffer_bytes = 0;  // maxStorageBufferRange
    uint64_t memory_bytes = 0;      // the largest device-local heap
};

// OK where a job over `gpu_scene` with `hit_points` (and a pixel job's uploads, `pixels`: pm's
// maps) fits `device`; RESOURCE_EXHAUSTED naming the buffer, the need and the limit otherwise.
absl::Status CheckJobFits(const DeviceCapacity& device, const GpuScene& gpu_scene,
                          size_t hit_points, const PixelJobData* pixels = nullptr);

struct JobBuffers;

// Threads of one photon or direct-light dispatch at most: enough to fill the largest GPUs
// (an H100 holds 270k resident threads), short enough to keep each dispatch brief; bigger
// batches run as several dispatches.
inline constexpr uint32_t kMaxThreadsPerDispatch = 1u << 20;
// Adaptive photon tracing's steps a chain, one chain a thread: 8192 threads for a batch of 2^19
// photons. Longer chains start more often where few photons count, but on lavapipe a thread's
// loop stopped after about 300 photon paths (256 steps of three paths ended near step 100, with
// the state and its stream defined throughout), so chains stay within it.
inline constexpr uint32_t kChainSteps = 64;

class VulkanBackend final : public Backend {
public:
    // A backend on `context`'s device for jobs over `scene` (which must outlive it), its path
    // tracer's design from PHOTONFARM_VULKAN_PATH (PathDesignFromEnvironment).
    static absl::StatusOr<std::unique_ptr<VulkanBackend>> Create(std::shared_ptr<Context> context,
                                                                 const Scene& scene);
    ~VulkanBackend() override;

    std::string_view Name() const override { return "vulkan"; }
    // Uploads the scene and hit points; RESOURCE_EXHAUSTED, naming the buffer and the limit,
    // where the job does not fit the device.
    absl::Status BeginJob(const JobInputs& job) override;
    absl::Status BeginEpoch(uint64_t epoch, const GatherRegions& regions,
                            const std::vector<HitPoint>* traced) override;
    absl::StatusOr<std::vector<BatchResult>> RunBatches(std::span<const BatchSpec> specs) override;

    const Context& GetContext() const { return *context_; }
    // Whether the current job traces paths through the wavefront's kernels.
    bool RunsPathWavefront() const { return wavefront_; }
    // The current job's scene features (what its kernels were specialised for).
    const SceneFeatures& Features() const { return features_; }

private:
    VulkanBackend(std::shared_ptr<Context> context, const Scene& scene, CommandStream stream,
                  PathDesign path_design);

    // The host's Embree tracer over the scene, made for the first job that needs one.
    absl::StatusOr<const Tracer*> CameraTracer();
    absl::StatusOr<BatchResult> RunBatch(const BatchSpec& spec);
    // ppm: traces the epoch pass's pixels that `specs`' direct-light slices lie in, unless
    // held already, and copies their points to the device where the whole pass's would lie.
    absl::Status UploadDirectPoints(std::span<const BatchSpec> specs);
    // A batch of the integrators that render pixels (path, pm).
    absl::StatusOr<BatchResult> RunPixelBatch(const BatchSpec& spec);
    // The finished batch's results, from the host-visible buffers.
    BatchResult ReadResult(const BatchSpec& spec) const;
    // Records an exclusive prefix sum of `count` elements of the array `target` (kScan*).
    void RecordScan(VkCommandBuffer commands, uint32_t target, uint32_t count);
    // Records `kernel` over `threads` threads from params.first = `first`, in dispatches of at
    // most kMaxThreadsPerDispatch within the device's workgroup count limit.
    void RecordThreads(VkCommandBuffer commands, Kernel kernel, gpu::GpuParams params,
                       uint64_t first, uint64_t threads);
    gpu::GpuParams BaseParams() const;

    std::shared_ptr<Context> context_;
    const Scene& scene_;
    CommandStream stream_;
    JobInputs job_;
    SceneFeatures features_;
    std::unique_ptr<Kernels> kernels_;
    std::unique_ptr<JobBuffers> buffers_;
    PathDesign path_design_;
    // Whether the job is the path tracer's and runs as a wavefront, and its rounds a sample at
    // most (the surfaces a path meets, and its escape).
    bool wavefront_ = false;
    uint64_t wavefront_rounds_per_sample_ = 0;
    // Whether the job is sppm's or rpm's, whose hit points change every epoch.
    bool StochasticJob() const { return passes_ && passes_->Stochastic(); }
    // Whether the job renders pixels (path, pm) rather than shooting photons into hit points.
    bool PixelJob() const {
        return job_.spec != nullptr && !GathersAtHitPoints(job_.spec->integrator);
    }
    // Whether the job traces its photons adaptively (JobSpec::photon_tracing).
    bool Adaptive() const {
        return job_.spec != nullptr && job_.spec->photon_tracing == PhotonTracing::kAdaptive;
    }

    // ppm, sppm, rpm: each epoch's camera passes, traced on the CPU through camera_tracer_
    // (made for the first job that needs it, pm's maps too): sppm's and rpm's hit points,
    // which job_.hit_points views (black slots, one per pixel sample, until the first epoch),
    // or the part of ppm's points of direct light that the batches run need
    // (UploadDirectPoints).
    std::optional<EpochPasses> passes_;
    std::unique_ptr<Tracer> camera_tracer_;
    std::vector<HitPoint> black_slots_;
    gpu::vec4 scene_sphere_{};
    float scene_magnitude_ = 0;
    float flux_to_fixed_ = 0;  // fixed-point tally units per watt
    uint32_t emitter_count_ = 0;
    uint32_t environment_emitter_ = 0;  // GpuScene::environment_emitter
    uint32_t buckets_ = 0;              // of the hit-point grid, a power of two
    float grid_inverse_cell_ = 0;
};

}  // namespace pf::vk
