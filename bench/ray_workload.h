/// \file ray_workload.h
/// \brief The three ray sets every contender traces, generated once, with Embree-robust answers.
#pragma once

#include <nori/camera.h>
#include <nori/ray.h>
#include <array>
#include <string>
#include <vector>

namespace nori {
class EmbreeOracle;
class MeshTable;
}

namespace nori::bench {

/// \brief One named ray set and the reference answer for each ray: the closest-hit t
/// (Infinity for a miss) or, for shadow rays, 0 (occluded) / Infinity (unoccluded).
struct RaySet {
    std::string name;          ///< "primary", "diffuse" or "shadow"
    bool shadow = false;       ///< traced with occluded() instead of intersect()
    std::vector<Ray3f> rays;
    std::vector<float> reference;

    size_t size() const { return rays.size(); }
    /// \brief Every \p stride-th ray (and its reference), for slow contenders.
    RaySet strided(size_t stride) const;
};

/// \brief The primary, diffuse and shadow sets of one benchmark case.
class RayWorkload {
public:
    static constexpr int Count = 3;

    /// \brief Generate the sets: camera rays from \p camera, one cosine bounce per primary
    /// hit, and a segment from each primary hit to a point light above the bounding box.
    /// Hits are found with \p robust, which also provides the reference answers.
    RayWorkload(const Camera &camera, int spp, const EmbreeOracle &robust, const MeshTable &table);
    RayWorkload(std::array<RaySet, Count> sets) : m_sets(std::move(sets)) {}

    const RaySet &set(int i) const { return m_sets[size_t(i)]; }
    const std::array<RaySet, Count> &sets() const { return m_sets; }
    /// \brief The same workload with at most \p maxRays rays per set (strided subsets).
    RayWorkload subset(size_t maxRays) const;
    size_t totalRays() const;

private:
    std::array<RaySet, Count> m_sets;
};

} // namespace nori::bench
