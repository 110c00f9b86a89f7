#version 460
// Grid build, step 2c: each block's offset added to its elements: grid_begin now holds the
// buckets' CSR offsets, grid_begin[buckets] the number of entries.
#include "common.glsl"

layout(local_size_x = kScanThreads) in;

void main() {
    const uint base = gl_WorkGroupID.x * kScanBlock;
    const uint offset = scan_blocks[gl_WorkGroupID.x];
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        if (base + k < params.scan_count) grid_begin[base + k] += offset;
}
