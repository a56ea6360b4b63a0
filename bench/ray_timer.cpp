/// \file ray_timer.cpp
/// \brief Traces a ray set through one intersector and times it (the only timed code) (implementation).
#include "ray_timer.h"
#include "embree_oracle.h"
#include <nori/accel.h>
#include <nori/cpu_clock.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <chrono>

namespace nori::bench {

namespace {
template <typename Tracer>
inline void traceRange(const Tracer &tracer, const RaySet &set, float *answers, size_t begin, size_t end) {
    const Ray3f *rays = set.rays.data();
    if (set.shadow) {
        for (size_t i = begin; i < end; ++i) answers[i] = tracer.occluded(rays[i]) ? 0.0f : Infinity;
    } else {
        for (size_t i = begin; i < end; ++i) {
            Hit hit;
            answers[i] = tracer.intersect(rays[i], hit) ? hit.t : Infinity;
        }
    }
}
} // namespace

template <typename Tracer>
double RayTimer::trace(const Tracer &tracer, const RaySet &set, std::vector<float> &answers) const {
    answers.assign(set.size(), -1.0f);  // touched before timing so page faults are not timed
    float *out = answers.data();
    if (m_cpuTime) {
        const double start = threadCpuMilliseconds();
        traceRange(tracer, set, out, 0, set.size());
        return threadCpuMilliseconds() - start;
    }
    auto start = std::chrono::steady_clock::now();
    if (m_threads == 1) {
        traceRange(tracer, set, out, 0, set.size());
    } else {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, set.size(), 256), [&](const tbb::blocked_range<size_t> &r) {
            traceRange(tracer, set, out, r.begin(), r.end());
        });
    }
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template double RayTimer::trace<Accel>(const Accel &, const RaySet &, std::vector<float> &) const;
template double RayTimer::trace<EmbreeOracle>(const EmbreeOracle &, const RaySet &, std::vector<float> &) const;

} // namespace nori::bench
