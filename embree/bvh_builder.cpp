// Embree's builder with our callbacks: it owns the temporary nodes (thread-local
// allocations freed with the RTCBVH), which are flattened into GpuBvhNode.
#include "embree/bvh_builder.h"

#include <embree3/rtcore.h>

#include <bit>
#include <memory>
#include <string>

#include "absl/strings/str_cat.h"
#include "core/util/check.h"
#include "embree/device.h"

namespace pf::embree {
namespace {

// The builder's nodes: an inner node with two children, or a leaf listing its primitives.
struct BuildNode {
    bool leaf;
};
struct InnerNode : BuildNode {
    BuildNode* children[2];
    RTCBounds bounds[2];
};
struct LeafNode : BuildNode {
    uint32_t count;
    uint32_t primitives[1];  // `count` of them, allocated past the end
};

void* CreateNode(RTCThreadLocalAllocator allocator, unsigned int child_count, void* /*user*/) {
    PF_CHECK(child_count == 2);
    void* memory = rtcThreadLocalAlloc(allocator, sizeof(InnerNode), 16);
    return new (memory) InnerNode{{false}, {nullptr, nullptr}, {}};
}

void SetNodeChildren(void* node, void** children, unsigned int child_count, void* /*user*/) {
    for (unsigned int i = 0; i < child_count; ++i)
        static_cast<InnerNode*>(node)->children[i] = static_cast<BuildNode*>(children[i]);
}

void SetNodeBounds(void* node, const RTCBounds** bounds, unsigned int child_count, void* /*user*/) {
    for (unsigned int i = 0; i < child_count; ++i)
        static_cast<InnerNode*>(node)->bounds[i] = *bounds[i];
}

void* CreateLeaf(RTCThreadLocalAllocator allocator, const RTCBuildPrimitive* primitives,
                 size_t count, void* /*user*/) {
    void* memory = rtcThreadLocalAlloc(allocator, sizeof(LeafNode) + count * sizeof(uint32_t), 16);
    auto* leaf = new (memory) LeafNode{{true}, static_cast<uint32_t>(count), {0}};
    for (size_t i = 0; i < count; ++i) leaf->primitives[i] = primitives[i].primID;
    return leaf;
}

gpu::vec4 Corner(float x, float y, float z, uint32_t bits) {
    return {x, y, z, std::bit_cast<float>(bits)};
}

// Appends `node`'s subtree below GPU node `parent`'s child `side`.
class Flattener {
public:
    explicit Flattener(GpuBvh& bvh) : bvh_(bvh) {}

    // The child reference and triangle count of a subtree: a leaf's primitives go to the
    // order list; an inner node becomes a GPU node.
    std::pair<uint32_t, uint32_t> Add(const BuildNode* node) {
        if (node->leaf) {
            const auto* leaf = static_cast<const LeafNode*>(node);
            const auto first = static_cast<uint32_t>(bvh_.order.size());
            bvh_.order.insert(bvh_.order.end(), leaf->primitives, leaf->primitives + leaf->count);
            return {first, leaf->count};
        }
        const auto* inner = static_cast<const InnerNode*>(node);
        const auto index = static_cast<uint32_t>(bvh_.nodes.size());
        bvh_.nodes.emplace_back();
        const auto [left, left_count] = Add(inner->children[0]);
        const auto [right, right_count] = Add(inner->children[1]);
        const RTCBounds& a = inner->bounds[0];
        const RTCBounds& b = inner->bounds[1];
        bvh_.nodes[index] = {Corner(a.lower_x, a.lower_y, a.lower_z, left),
                             Corner(a.upper_x, a.upper_y, a.upper_z, left_count),
                             Corner(b.lower_x, b.lower_y, b.lower_z, right),
                             Corner(b.upper_x, b.upper_y, b.upper_z, right_count)};
        return {index, 0};
    }

private:
    GpuBvh& bvh_;
};

// The BVH, released before its device.
struct BuiltBvh {
    RTCBVH bvh = nullptr;
    ~BuiltBvh() {
        if (bvh) rtcReleaseBVH(bvh);
    }
};

}  // namespace

absl::StatusOr<GpuBvh> BuildGpuBvh(std::span<const Bounds> boxes) {
    PF_CHECK(!boxes.empty());
    absl::StatusOr<Device> device = Device::Create();
    if (!device.ok()) return device.status();
    BuiltBvh handles;
    handles.bvh = rtcNewBVH(device->Handle());
    // Binned SAH without spatial splits: the builder may then not grow the primitive array.
    std::vector<RTCBuildPrimitive> primitives(boxes.size());
    for (size_t i = 0; i < boxes.size(); ++i) {
        const Bounds& box = boxes[i];
        primitives[i] = {.lower_x = box.lower.x,
                         .lower_y = box.lower.y,
                         .lower_z = box.lower.z,
                         .geomID = 0,
                         .upper_x = box.upper.x,
                         .upper_y = box.upper.y,
                         .upper_z = box.upper.z,
                         .primID = static_cast<unsigned>(i)};
    }
    RTCBuildArguments arguments = rtcDefaultBuildArguments();
    arguments.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    arguments.maxBranchingFactor = 2;
    arguments.maxDepth = gpu::kMaxBvhDepth;
    arguments.minLeafSize = 1;
    arguments.maxLeafSize = 4;
    arguments.traversalCost = 1.0f;
    arguments.intersectionCost = 1.0f;
    arguments.bvh = handles.bvh;
    arguments.primitives = primitives.data();
    arguments.primitiveCount = primitives.size();
    arguments.primitiveArrayCapacity = primitives.size();
    arguments.createNode = CreateNode;
    arguments.setNodeChildren = SetNodeChildren;
    arguments.setNodeBounds = SetNodeBounds;
    arguments.createLeaf = CreateLeaf;
    const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&arguments));
    if (root == nullptr || !device->LastError().empty())
        return absl::InternalError(device->LastError().empty()
                                       ? "Embree's BVH builder returned nothing"
                                       : "Embree's BVH builder: " + device->LastError());
    GpuBvh bvh;
    Flattener flattener(bvh);
    if (root->leaf) {
        // The traversal starts at an inner node: a lone leaf becomes both children of one
        // (its triangles tested twice, which finds nothing new).
        const auto [first, count] = flattener.Add(root);
        const Bounds all = [&] {
            Bounds b;
            for (const Bounds& box : boxes) b.Extend(box.lower), b.Extend(box.upper);
            return b;
        }();
        const gpu::vec4 lower = Corner(all.lower.x, all.lower.y, all.lower.z, first);
        const gpu::vec4 upper = Corner(all.upper.x, all.upper.y, all.upper.z, count);
        bvh.nodes.push_back({lower, upper, lower, upper});
    } else {
        flattener.Add(root);
    }
    return bvh;
}

}  // namespace pf::embree
