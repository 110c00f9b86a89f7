// The one Embree device set-up: every Embree object photonfarm makes (the tracer's scenes, the
// Vulkan backend's BVH build) comes from a Device, whose one error callback logs Embree's
// message and keeps it for the caller to turn into a Status.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace pf::embree {

// Owns an RTCDevice. Movable, not copyable; the error slot has a fixed address for the
// callback. Not thread-safe for errors: the last error of any thread is kept.
class Device {
public:
    // UNAVAILABLE when Embree cannot make a device (a CPU without SSE2, a broken install, a
    // bad PF_EMBREE_CONFIG). The environment's PF_EMBREE_CONFIG is Embree's configuration.
    static absl::StatusOr<Device> Create();

    RTCDevice Handle() const { return state_->device; }
    // The last error Embree reported on this device ("Embree error 2: out of memory"), or
    // empty.
    const std::string& LastError() const { return state_->last_error; }

private:
    struct State {
        RTCDevice device = nullptr;
        std::string last_error;
        ~State();
    };
    explicit Device(std::unique_ptr<State> state) : state_(std::move(state)) {}
    std::unique_ptr<State> state_;
};

}  // namespace pf::embree
