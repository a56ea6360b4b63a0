/// \file brute.cpp
/// \brief Brute-force accelerator: tests every triangle. Reference and baseline only.
#include "triangle.h"

namespace nori {

/// \brief `<accel type="brute">`: one leaf holding every triangle, tested with the same
/// TriangleStore kernels as the octree's leaves (16 triangles at a time, skipping the
/// blocks of triangles whose box the ray misses). Property: `intersector` (mt | watertight).
class BruteAccel : public Accel {
public:
    explicit BruteAccel(const PropertyList &props) : m_intersector(parseIntersector(props, "watertight")) {}

    bool intersect(const Ray3f &ray, Hit &hit) const override {
        Hit best;
        best.t = ray.maxt;
        if (!m_triangles.intersect(TriangleRay(ray), 0, m_count, best)) return false;
        hit = best;
        return true;
    }

    bool occluded(const Ray3f &ray) const override {
        return m_triangles.occluded(TriangleRay(ray), 0, m_count, ray.maxt);
    }

    std::vector<AccelStat> statistics() const override {
        std::vector<AccelStat> stats = Accel::statistics();
        stats.push_back({"bytes", double(m_triangles.bytes()), true});
        return stats;
    }

    std::string toString() const override {
        return fmt::format("BruteAccel[intersector={}]", intersectorName(m_intersector));
    }

protected:
    void buildImpl() override {
        // Same input rule as the octree: triangles no ray can hit are left out.
        std::vector<std::array<Point3f, 3>> vertices(triangleCount());
        std::vector<uint32_t> prims;
        prims.reserve(triangleCount());
        for (size_t m = 0; m < m_meshes.size(); ++m)
            for (uint32_t f = 0; f < m_meshes[m]->triangleCount(); ++f) {
                uint32_t prim = m_offsets[m] + f;
                auto &v = vertices[prim];
                for (int k = 0; k < 3; ++k) v[k] = m_meshes[m]->vertex(f, k);
                if (triangleCanBeHit(v)) prims.push_back(prim);
            }
        m_count = uint32_t(prims.size());
        m_triangles.reset(m_intersector, TriangleStore::leafWords(m_count));
        m_triangles.setLeaf(0, prims.data(), m_count, vertices);
    }

private:
    Intersector m_intersector;
    TriangleStore m_triangles;
    uint32_t m_count = 0;  ///< triangles in the single leaf
};

NORI_REGISTER_CLASS(BruteAccel, "brute", EAccel);

} // namespace nori
