#version 460
// Grid build, step 1: how many hit points each bucket holds (counts in grid_begin, zeroed).
#include "common.glsl"
#include "grid.glsl"

layout(local_size_x = kWorkgroupSize) in;

void main() {
    const uint hit_point = gl_GlobalInvocationID.x;
    if (hit_point >= params.hit_point_count || !GridHolds(hit_point)) return;
    atomicAdd(grid_begin[GridBucket(GridCell(hit_points[hit_point].position.xyz))], 1u);
}
