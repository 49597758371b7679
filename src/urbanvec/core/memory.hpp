// Resident memory of this process (Linux /proc/self/status), for the per-stage figures of
// `vectorize -timings`; elsewhere every figure is -1 and the reset does nothing.
#pragma once

namespace urbanvec {

/// The kernel's resident-memory high-water mark (VmHWM) in kB since the last resetPeakMemory(), -1
/// when unknown.
long peakMemoryKb();

/// Resident memory now (VmRSS) in kB, -1 when unknown.
long residentMemoryKb();

/// Remembers the current high-water mark (processPeakMemoryKb) and resets the kernel's one (Linux
/// "clear_refs" 5), so that the next peakMemoryKb() is the peak of what follows.
void resetPeakMemory();

/// The highest resident memory of the whole process so far in kB, across resetPeakMemory() calls;
/// -1 when unknown. (A reset also hides the earlier peak from getrusage, so `/usr/bin/time` sees
/// only the peak since the last reset: this is the figure to compare.)
long processPeakMemoryKb();

/// Hands the heap pages that freed memory left behind back to the system (glibc's malloc_trim; a no-op
/// elsewhere). The GEOS stages free hundreds of MB of small objects at city scale; with glibc's malloc
/// they stay resident without this and the next stage's allocations pile on top of them. The urbanvec
/// command links mimalloc, which returns freed pages by itself: there this trims glibc's nearly empty
/// heap only (calling mimalloc's mi_collect(true) instead was measured: 4096² peak 890 -> 898 MB, no
/// gain).
void releaseFreedMemory();

}  // namespace urbanvec
