/// \file embree_accel.h
/// \brief `<accel type="embree">`: Embree 3 behind nori::Accel, for nori-bench's full-render mode only.
#pragma once

#include <nori/accel.h>
#include <memory>

namespace nori {

class EmbreeOracle;

namespace bench {

/// \brief An Accel whose queries go to Embree (rtcIntersect1 / rtcOccluded1). It fills the
/// same Hit (t, barycentrics of corners 1 and 2, global triangle id) as the octree, so
/// Accel::completeIntersection and every integrator work unchanged: a scene rendered with it
/// differs from the octree's render only where the two disagree on a ray.
///
/// Registered in nori-bench only (the renderer never links Embree). Properties:
/// `robust` (boolean, default false: Embree's default scene flags, the speed peer) and
/// `threads` (integer, default 0: Embree's own default; the bench passes --threads).
class EmbreeAccel : public Accel {
public:
    explicit EmbreeAccel(const PropertyList &props);
    ~EmbreeAccel() override;

    bool intersect(const Ray3f &ray, Hit &hit) const override;
    bool occluded(const Ray3f &ray) const override;
    std::vector<AccelStat> statistics() const override;
    std::string toString() const override;

protected:
    void buildImpl() override;

private:
    bool m_robust;
    int m_threads;
    std::unique_ptr<EmbreeOracle> m_embree;
};

} // namespace bench
} // namespace nori
