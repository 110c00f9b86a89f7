#version 460
// Grid build, step 2a: each block of the bucket counts scanned in place, its total kept.
#include "common.glsl"
#include "scan.glsl"

layout(local_size_x = kScanThreads) in;

void main() {
    const uint base = gl_WorkGroupID.x * kScanBlock;
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        scan_values[k] = base + k < params.scan_count ? grid_begin[base + k] : 0u;
    const uint total = ScanBlock();
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        if (base + k < params.scan_count) grid_begin[base + k] = scan_values[k];
    if (gl_LocalInvocationID.x == 0) scan_blocks[gl_WorkGroupID.x] = total;
}
