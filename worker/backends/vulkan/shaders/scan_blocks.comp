#version 460
// Prefix sum, step 1: each block of the counts scanned in place, its total kept.
#include "common.glsl"
#include "scan.glsl"

layout(local_size_x = kScanThreads) in;

void main() {
    const uint base = gl_WorkGroupID.x * kScanBlock;
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        scan_values[k] = base + k < params.scan_count ? ScanLoad(base + k) : 0u;
    const uint total = ScanBlock();
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        if (base + k < params.scan_count) ScanStore(base + k, scan_values[k]);
    if (gl_LocalInvocationID.x == 0) scan_blocks[gl_WorkGroupID.x] = total;
}
