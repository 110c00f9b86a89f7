// The backend registry: one line per backend.
#include "worker/backend_factory.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "embree/embree_tracer.h"
#include "worker/backends/cpu_embree/cpu_backend.h"
#include "worker/backends/vulkan/vulkan_backend.h"

namespace pf {
namespace {

// The CPU backend with the Embree scene it traces, owned together.
class OwningCpuBackend final : public Backend {
public:
    explicit OwningCpuBackend(std::unique_ptr<embree::EmbreeTracer> tracer)
        : tracer_(std::move(tracer)), backend_(*tracer_) {}

    std::string_view Name() const override { return backend_.Name(); }
    absl::Status BeginJob(const JobInputs& job) override { return backend_.BeginJob(job); }
    absl::Status BeginEpoch(uint64_t epoch, const GatherRegions& regions,
                            const std::vector<HitPoint>* traced) override {
        return backend_.BeginEpoch(epoch, regions, traced);
    }
    absl::StatusOr<std::vector<BatchResult>> RunBatches(std::span<const BatchSpec> specs) override {
        return backend_.RunBatches(specs);
    }

private:
    std::unique_ptr<embree::EmbreeTracer> tracer_;
    embree::CpuBackend backend_;
};

}  // namespace

absl::StatusOr<BackendDevice> OpenBackendDevice(std::string_view name) {
    if (name != "vulkan") return BackendDevice{nullptr, std::string(name)};
    absl::StatusOr<std::shared_ptr<vk::Context>> context = vk::Context::Shared();
    if (!context.ok())
        return absl::Status(context.status().code(),
                            absl::StrCat("vulkan backend: ", context.status().message()));
    std::string description = absl::StrCat("vulkan: ", (*context)->Info().name);
    return BackendDevice{std::move(*context), std::move(description)};
}

uint64_t BackendValidationErrors() { return vk::Context::ValidationErrors(); }

std::string DescribeDevices(int cpu_threads) {
    std::string lines = absl::StrCat("cpu: Embree, ", cpu_threads, " threads\n");
    absl::StatusOr<std::vector<vk::DeviceInfo>> devices = vk::ListDevices();
    if (!devices.ok())
        return absl::StrCat(lines, "vulkan: unavailable: ", devices.status().message(), "\n");
    if (devices->empty()) return absl::StrCat(lines, "vulkan: no devices\n");
    const absl::StatusOr<uint32_t> chosen = vk::ChooseDevice(*devices);
    for (const vk::DeviceInfo& device : *devices) {
        absl::StrAppend(&lines, "vulkan device ", device.index, ": ", device.name, " (",
                        device.type, ", Vulkan ", device.api_version, ", ",
                        device.device_local_bytes >> 20, " MiB)");
        if (!device.unusable.empty()) absl::StrAppend(&lines, ": unusable: ", device.unusable);
        if (chosen.ok() && *chosen == device.index)
            absl::StrAppend(&lines, "  <- --backend vulkan uses this one");
        absl::StrAppend(&lines, "\n");
    }
    if (!chosen.ok()) absl::StrAppend(&lines, "vulkan: ", chosen.status().message(), "\n");
    return lines;
}

absl::StatusOr<std::unique_ptr<Backend>> CreateBackend(std::string_view name, const Scene& scene) {
    if (name == "cpu") {
        absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer =
            embree::EmbreeTracer::Create(scene);
        if (!tracer.ok()) return tracer.status();
        return std::unique_ptr<Backend>(std::make_unique<OwningCpuBackend>(std::move(*tracer)));
    }
    if (name == "vulkan") {
        absl::StatusOr<std::shared_ptr<vk::Context>> context = vk::Context::Shared();
        if (!context.ok())
            return absl::Status(context.status().code(),
                                absl::StrCat("vulkan backend: ", context.status().message()));
        absl::StatusOr<std::unique_ptr<vk::VulkanBackend>> backend =
            vk::VulkanBackend::Create(std::move(*context), scene);
        if (!backend.ok()) return backend.status();
        return std::unique_ptr<Backend>(std::move(*backend));
    }
    return absl::InvalidArgumentError(
        absl::StrCat("unknown backend '", std::string(name),
                     "' (known: ", absl::StrJoin(BackendNames(), ", "), ")"));
}

}  // namespace pf
