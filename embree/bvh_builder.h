// A BVH for the Vulkan backend's own traversal, built by Embree's BVH builder
// (rtcBuildBVH: binned SAH, multithreaded) through node and leaf callbacks, then flattened
// depth-first into the GPU's two-wide nodes. Here because every rtc* call lives in this folder.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/shared/gpu_types.h"

namespace pf::embree {

struct GpuBvh {
    std::vector<gpu::GpuBvhNode> nodes;  // nodes[0] is the root; leaves index `order`
    std::vector<uint32_t> order;         // primitive indices in leaf order
};

// A BVH over the boxes (one per primitive, at least one). INTERNAL with Embree's message
// should the builder fail.
absl::StatusOr<GpuBvh> BuildGpuBvh(std::span<const Bounds> boxes);

}  // namespace pf::embree
