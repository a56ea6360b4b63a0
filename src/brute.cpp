/// Brute-force accelerator: tests every triangle. Reference and baseline only.
#include <nori/accel.h>

namespace nori {

namespace {
/// Möller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection".
bool intersectTriangleMT(const Ray3f &ray, const Point3f &p0, const Point3f &p1, const Point3f &p2, float maxt,
                         float &t, float &u, float &v) {
    Vector3f e1 = p1 - p0, e2 = p2 - p0;
    Vector3f pvec = ray.d.cross(e2);
    float det = e1.dot(pvec);
    if (det == 0.0f) return false;
    float invDet = 1.0f / det;
    Vector3f tvec = ray.o - p0;
    u = tvec.dot(pvec) * invDet;
    if (u < 0.0f || u > 1.0f) return false;
    Vector3f qvec = tvec.cross(e1);
    v = ray.d.dot(qvec) * invDet;
    if (v < 0.0f || u + v > 1.0f) return false;
    t = e2.dot(qvec) * invDet;
    return t >= ray.mint && t <= maxt;
}
} // namespace

class BruteAccel : public Accel {
public:
    explicit BruteAccel(const PropertyList &) {}

    bool intersect(const Ray3f &ray, Hit &hit) const override {
        bool found = false;
        float maxt = ray.maxt;
        for (size_t m = 0; m < m_meshes.size(); ++m) {
            const Mesh *mesh = m_meshes[m];
            for (uint32_t f = 0; f < mesh->triangleCount(); ++f) {
                float t, u, v;
                if (intersectTriangleMT(ray, mesh->vertex(f, 0), mesh->vertex(f, 1), mesh->vertex(f, 2), maxt, t, u, v)) {
                    maxt = t;
                    hit = Hit{t, u, v, m_offsets[m] + f};
                    found = true;
                }
            }
        }
        return found;
    }

    bool occluded(const Ray3f &ray) const override {
        for (const Mesh *mesh : m_meshes)
            for (uint32_t f = 0; f < mesh->triangleCount(); ++f) {
                float t, u, v;
                if (intersectTriangleMT(ray, mesh->vertex(f, 0), mesh->vertex(f, 1), mesh->vertex(f, 2), ray.maxt, t, u, v))
                    return true;
            }
        return false;
    }

    std::string toString() const override { return "BruteAccel[]"; }

protected:
    void buildImpl() override {}
};

NORI_REGISTER_CLASS(BruteAccel, "brute", EAccel);

} // namespace nori
