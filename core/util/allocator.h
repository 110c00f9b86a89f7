// Process-wide allocator settings for photonfarm's executables, called first thing in main().
#pragma once

namespace pf {

// Tallies, radii and messages of megabytes are allocated and freed many times a second. With
// glibc's defaults each thread allocates from an arena of its own whose heaps give freed
// buffers of that size back to the kernel, so each new one costs its pages again in page
// faults: a third of the coordinator's CPU time in a farm run, measured. This keeps one
// arena and keeps freed memory for reuse (bench/farm_vs_render.sh shows the difference).
void KeepLargeBuffersForReuse();

}  // namespace pf
