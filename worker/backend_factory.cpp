// The backend registry: one line per backend.
#include "worker/backend_factory.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "worker/backends/cpu_embree/cpu_backend.h"
#include "worker/backends/cpu_embree/embree_tracer.h"

namespace pf {
namespace {

// The CPU backend with the Embree scene it traces, owned together.
class OwningCpuBackend final : public Backend {
public:
    explicit OwningCpuBackend(std::unique_ptr<embree::EmbreeTracer> tracer)
        : tracer_(std::move(tracer)), backend_(*tracer_) {}

    std::string_view Name() const override { return backend_.Name(); }
    absl::Status BeginJob(const JobInputs& job) override { return backend_.BeginJob(job); }
    void BeginEpoch(std::span<const float> radius_sq) override { backend_.BeginEpoch(radius_sq); }
    std::vector<BatchResult> RunBatches(std::span<const BatchSpec> specs) override { return backend_.RunBatches(specs); }

private:
    std::unique_ptr<embree::EmbreeTracer> tracer_;
    embree::CpuBackend backend_;
};

}  // namespace

std::vector<std::string> BackendNames() { return {"cpu"}; }

absl::StatusOr<std::unique_ptr<Backend>> CreateBackend(std::string_view name, const Scene& scene) {
    if (name == "cpu") {
        absl::StatusOr<std::unique_ptr<embree::EmbreeTracer>> tracer = embree::EmbreeTracer::Create(scene);
        if (!tracer.ok()) return tracer.status();
        return std::unique_ptr<Backend>(std::make_unique<OwningCpuBackend>(std::move(*tracer)));
    }
    return absl::InvalidArgumentError(
        absl::StrCat("unknown backend '", std::string(name), "' (known: ", absl::StrJoin(BackendNames(), ", "), ")"));
}

}  // namespace pf
