/// \file heap_policy.h
/// \brief The bench programs' malloc settings: memory one build frees stays in the process for
/// the next build.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace nori::bench {

/// glibc returns a freed block above its mmap threshold (dynamic, at most 32 MiB) to the
/// system at once, and trims the heap's free top above twice that; the next build maps the
/// same memory again, one page fault per 4 KiB page. Under this hypervisor a fault costs
/// about 13 us of the thread's CPU time: the second and third octree builds of a 100k-triangle
/// scene took 900 and 300 faults, up to half again their fault-free time, and moved by 1.5x from
/// run to run. The bench compares the median of repeated builds, so it keeps blocks below
/// 32 MiB in the heap and the heap's free memory up to 256 MiB: every contender in the
/// process (Embree too) then reuses what its previous build freed. A renderer builds once;
/// its first build, faults included, is the same with or without this.
inline void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

} // namespace nori::bench
