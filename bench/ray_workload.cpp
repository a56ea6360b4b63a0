/// \file ray_workload.cpp
/// \brief The three ray sets every contender traces, generated once, with Embree-robust answers (implementation).
#include "ray_workload.h"
#include "embree_oracle.h"
#include "ray_sets.h"

namespace nori::bench {

RaySet RaySet::strided(size_t stride) const {
    RaySet out;
    out.name = name;
    out.shadow = shadow;
    if (stride == 0) stride = 1;
    for (size_t i = 0; i < rays.size(); i += stride) {
        out.rays.push_back(rays[i]);
        out.reference.push_back(reference[i]);
    }
    return out;
}

RayWorkload::RayWorkload(const Camera &camera, int spp, const EmbreeOracle &robust, const MeshTable &table) {
    // Fixed seeds: every contender, every run and every machine gets the same rays.
    const uint64_t cameraSeed = 0x6e6f7269u, diffuseSeed = 0x62656e63u;
    ClosestHitFunction hitFunction = [&robust](const Ray3f &ray, Hit &hit) { return robust.intersect(ray, hit); };

    m_sets[0].name = "primary";
    m_sets[0].rays = cameraRays(camera, spp, cameraSeed);
    m_sets[1].name = "diffuse";
    m_sets[1].rays = diffuseRays(m_sets[0].rays, hitFunction, table, diffuseSeed);
    m_sets[2].name = "shadow";
    m_sets[2].shadow = true;
    m_sets[2].rays = lightShadowRays(m_sets[0].rays, hitFunction, table, lightAbove(table.bbox()));

    for (RaySet &set : m_sets) {
        set.reference.resize(set.rays.size());
        for (size_t i = 0; i < set.rays.size(); ++i) {
            if (set.shadow) {
                set.reference[i] = robust.occluded(set.rays[i]) ? 0.0f : Infinity;
            } else {
                Hit hit;
                set.reference[i] = robust.intersect(set.rays[i], hit) ? hit.t : Infinity;
            }
        }
    }
}

RayWorkload RayWorkload::subset(size_t maxRays) const {
    std::array<RaySet, Count> sets;
    for (int i = 0; i < Count; ++i) {
        size_t n = m_sets[size_t(i)].size();
        size_t stride = maxRays == 0 || n <= maxRays ? 1 : (n + maxRays - 1) / maxRays;
        sets[size_t(i)] = m_sets[size_t(i)].strided(stride);
    }
    return RayWorkload(std::move(sets));
}

size_t RayWorkload::totalRays() const {
    size_t n = 0;
    for (const RaySet &s : m_sets) n += s.size();
    return n;
}

} // namespace nori::bench
