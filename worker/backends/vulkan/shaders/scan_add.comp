#version 460
// Prefix sum, step 3: each block's offset added to its elements. For the grid, grid_begin
// then holds the buckets' CSR offsets and grid_begin[buckets] the number of entries; for the
// tally, tally_offsets[i] is hit point i's entry and tally_offsets[hit points] their number.
#include "common.glsl"
#include "scan.glsl"

layout(local_size_x = kScanThreads) in;

void main() {
    const uint base = gl_WorkGroupID.x * kScanBlock;
    const uint offset = scan_blocks[gl_WorkGroupID.x];
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        if (base + k < params.scan_count) ScanStore(base + k, ScanLoad(base + k) + offset);
}
