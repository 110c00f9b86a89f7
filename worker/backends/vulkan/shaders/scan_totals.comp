#version 460
// Prefix sum, step 2: the block totals scanned in place by one workgroup, kScanBlock at a
// time with the running sum carried, so any number of blocks fits.
#include "common.glsl"
#include "scan.glsl"

layout(local_size_x = kScanThreads) in;

void main() {
    uint carried = 0;
    for (uint base = 0; base < params.scan_count; base += kScanBlock) {
        for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
            scan_values[k] = base + k < params.scan_count ? scan_blocks[base + k] : 0u;
        const uint total = ScanBlock();
        for (uint k = gl_LocalInvocationID.x; k < kScanBlock; k += kScanThreads)
            if (base + k < params.scan_count) scan_blocks[base + k] = scan_values[k] + carried;
        carried += total;
    }
}
