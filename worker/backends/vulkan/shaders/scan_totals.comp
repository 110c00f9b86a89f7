#version 460
// Grid build, step 2b: the block totals scanned in place by one workgroup (at most
// kScanBlock blocks: the bucket count is capped to fit).
#include "common.glsl"
#include "scan.glsl"

layout(local_size_x = kScanThreads) in;

void main() {
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        scan_values[k] = k < params.scan_count ? scan_blocks[k] : 0u;
    ScanBlock();
    for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
        if (k < params.scan_count) scan_blocks[k] = scan_values[k];
}
