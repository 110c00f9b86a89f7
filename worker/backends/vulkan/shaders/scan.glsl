// An exclusive prefix sum over kScanBlock values in shared memory, by one workgroup of
// kScanThreads: each thread scans its kScanPerThread consecutive values serially, the
// threads' totals are scanned in shared memory (Hillis and Steele 1986), and each thread
// adds its offset. Callers load `scan_values`, call ScanBlock, and store it back. The array
// scanned in the end is params.scan_target's (ScanLoad, ScanStore).
uint ScanLoad(uint i) { return params.scan_target == kScanGridBegin ? grid_begin[i] : tally_offsets[i]; }
void ScanStore(uint i, uint value) {
    if (params.scan_target == kScanGridBegin) grid_begin[i] = value;
    else tally_offsets[i] = value;
}

shared uint scan_values[kScanBlock];
shared uint thread_totals[kScanThreads];

// Returns the block's total (the sum of every value) to every thread.
uint ScanBlock() {
    const uint thread = gl_LocalInvocationID.x;
    const uint base = thread * kScanPerThread;
    barrier();
    uint running = 0;
    for (uint k = 0; k < kScanPerThread; ++k) {
        const uint value = scan_values[base + k];
        scan_values[base + k] = running;
        running += value;
    }
    thread_totals[thread] = running;
    barrier();
    for (uint stride = 1; stride < kScanThreads; stride *= 2) {
        const uint add = thread >= stride ? thread_totals[thread - stride] : 0u;
        barrier();
        thread_totals[thread] += add;
        barrier();
    }
    const uint offset = thread_totals[thread] - running;
    for (uint k = 0; k < kScanPerThread; ++k) scan_values[base + k] += offset;
    const uint total = thread_totals[kScanThreads - 1];
    barrier();
    return total;
}
