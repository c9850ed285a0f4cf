#pragma once

namespace mm::sim {

/// Makes the process's allocator keep freed memory for later allocations instead of returning it
/// to the system (glibc: blocks up to 32 MiB from the heap, trimmed only above 256 MiB free; no
/// effect elsewhere). For executables that run many simulations one after another on each thread:
/// every run allocates the same few megabytes of planner buffers (an `ego_sweep`'s placements, the
/// clearance fields), and with glibc's defaults each run had the system map and zero them anew —
/// 283,000 page faults and 0.7 s of system time in the `table1` sweep (docs/performance.md,
/// "Sweeps"). Call once at the start of `main`, before any thread starts.
void retain_freed_memory();

}  // namespace mm::sim
