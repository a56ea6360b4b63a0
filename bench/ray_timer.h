/// \file ray_timer.h
/// \brief Traces a ray set through one intersector and times it (the only timed code).
#pragma once

#include "ray_workload.h"
#include <vector>

namespace nori::bench {

/// \brief Times one pass of a ray set. Single-threaded it is a plain loop over the rays;
/// with more threads, a tbb::parallel_for over chunks of rays.
class RayTimer {
public:
    /// \p cpuTime: measure the calling thread's CPU time (threads == 1 only).
    RayTimer(int threads, bool cpuTime) : m_threads(threads), m_cpuTime(cpuTime && threads == 1) {}

    /// \brief Trace every ray of \p set with \p tracer (nori::Accel or nori::EmbreeOracle),
    /// write one answer per ray to \p answers (as RaySet::reference) and return milliseconds.
    template <typename Tracer>
    double trace(const Tracer &tracer, const RaySet &set, std::vector<float> &answers) const;

private:
    int m_threads;
    bool m_cpuTime;
};

} // namespace nori::bench
