// The Embree device and its one error callback.
#include "embree/device.h"

#include <spdlog/spdlog.h>

#include <cstdlib>

#include "absl/strings/str_cat.h"

namespace pf::embree {
namespace {

void OnEmbreeError(void* user, RTCError code, const char* message) {
    auto* last_error = static_cast<std::string*>(user);
    *last_error =
        absl::StrCat("Embree error ", static_cast<int>(code), ": ", message ? message : "");
    spdlog::error("{}", *last_error);
}

}  // namespace

Device::State::~State() {
    if (device) rtcReleaseDevice(device);
}

absl::StatusOr<Device> Device::Create() {
    auto state = std::make_unique<State>();
    // PF_EMBREE_CONFIG: Embree's own configuration ("isa=sse4.2" holds its kernels to one
    // instruction set, so machines of other CPUs trace the same hits: the golden image test).
    const char* config = std::getenv("PF_EMBREE_CONFIG");
    state->device = rtcNewDevice(config);
    if (state->device == nullptr)
        return absl::UnavailableError(
            absl::StrCat("cannot create an Embree device",
                         config ? absl::StrCat(" with PF_EMBREE_CONFIG \"", config, "\"") : "",
                         " (CPU without SSE2?)"));
    rtcSetDeviceErrorFunction(state->device, OnEmbreeError, &state->last_error);
    return Device(std::move(state));
}

}  // namespace pf::embree
