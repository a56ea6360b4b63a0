/// \file cpu_clock.h
/// \brief The calling thread's CPU time, for timings that a shared machine's other work should
/// not inflate (nori-bench --cpu-time: builds and ray sets on one thread).
#pragma once

#include <ctime>

namespace nori {

/// \brief Milliseconds of CPU time the calling thread has used (CLOCK_THREAD_CPUTIME_ID).
inline double threadCpuMilliseconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

} // namespace nori
