#version 460
// Tally compaction, step 1: a 1 for every hit point the batch's photons reached (and a 0
// past the last), for the prefix sum that gives each its entry.
#include "common.glsl"

layout(local_size_x = kWorkgroupSize) in;

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i < params.hit_point_count) tally_offsets[i] = tally[i].photons > 0 ? 1u : 0u;
    else if (i == params.hit_point_count) tally_offsets[i] = 0u;
}
