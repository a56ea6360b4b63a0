/// \file embree_accel.cpp
/// \brief Embree 3 as a nori::Accel (nori-bench's full-render mode).
#include "embree_accel.h"
#include "embree_oracle.h"

namespace nori::bench {

EmbreeAccel::EmbreeAccel(const PropertyList &props)
    : m_robust(props.getBoolean("robust", false)), m_threads(props.getInteger("threads", 0)) {
    if (m_threads < 0) throw NoriException("embree accel: threads must be >= 0 (got {})", m_threads);
}

EmbreeAccel::~EmbreeAccel() = default;

void EmbreeAccel::buildImpl() {
    EmbreeOracle::Options options;
    options.robust = m_robust;
    options.threads = m_threads;
    m_embree = std::make_unique<EmbreeOracle>(m_meshes, options);
}

bool EmbreeAccel::intersect(const Ray3f &ray, Hit &hit) const { return m_embree->intersect(ray, hit); }

bool EmbreeAccel::occluded(const Ray3f &ray) const { return m_embree->occluded(ray); }

std::vector<AccelStat> EmbreeAccel::statistics() const {
    std::vector<AccelStat> stats = Accel::statistics();
    if (m_embree) stats.push_back({"bytes", double(m_embree->bytes()), true});
    return stats;
}

std::string EmbreeAccel::toString() const {
    return fmt::format("EmbreeAccel[robust={}, threads={}]", m_robust, m_threads);
}

NORI_REGISTER_CLASS(EmbreeAccel, "embree", EAccel);

} // namespace nori::bench
