#version 460
// Tally compaction, step 3: every reached hit point's sums written to its entry, in hit point
// order, straight into host-visible memory, with the flux converted from fixed point to
// watts; only the entries cross to the host, not a slot for every hit point.
#include "common.glsl"

layout(local_size_x = kWorkgroupSize) in;

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i == params.hit_point_count) counters.tally_entries = uint64_t(tally_offsets[i]);
    if (i >= params.hit_point_count || tally[i].photons == 0) return;
    const GpuTallySum sum = tally[i];
    const float watts_per_unit = 1.0 / params.flux_to_fixed;
    GpuTallyEntry entry;
    entry.hit_point = i;
    entry.photons = sum.photons;
    entry.inner_photons = sum.inner_photons;
    for (uint c = 0; c < 3; ++c) entry.flux[c] = float(sum.flux[c]) * watts_per_unit;
    tally_entries[tally_offsets[i]] = entry;
}
