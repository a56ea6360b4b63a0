// Ray/triangle intersectors and the leaf triangle store.
// No FMA contraction in this file: see triangle.h for why results must be bit-reproducible.
#pragma GCC optimize("fp-contract=off")

#include <nori/triangle.h>
#include <cmath>
#include <cstring>

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#include <immintrin.h>
#define NORI_TRIANGLE_AVX512 1
#endif

namespace nori {

Intersector parseIntersector(const PropertyList &props, const std::string &defaultValue) {
    std::string name = props.getString("intersector", defaultValue);
    if (name == "mt") return Intersector::MT;
    if (name == "watertight") return Intersector::Watertight;
    props.fail("intersector", fmt::format("unknown intersector '{}' (allowed: mt, watertight)", name));
}

const char *intersectorName(Intersector kind) { return kind == Intersector::MT ? "mt" : "watertight"; }

TriangleRay::TriangleRay(const Ray3f &ray) {
    for (int i = 0; i < 3; ++i) {
        o[i] = ray.o[i];
        d[i] = ray.d[i];
    }
    mint = ray.mint;
    // Woop et al. 2013, section 3: shear/scale so that the ray becomes the +z axis.
    float ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
    kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < 0.0f) std::swap(kx, ky);
    sx = d[kx] / d[kz];
    sy = d[ky] / d[kz];
    sz = 1.0f / d[kz];
}

// ---------------------------------------------------------------------------------------------
// Scalar kernels. The SIMD kernels below perform the same IEEE operations in the same order.

bool intersectMT(const TriangleRay &r, const float v0[3], const float e1[3], const float e2[3], float maxt,
                 float &t, float &u, float &v) {
    // Möller & Trumbore 1997: Cramer's rule on [-d, e1, e2] (t, u, v) = o - v0.
    float px = r.d[1] * e2[2] - r.d[2] * e2[1];
    float py = r.d[2] * e2[0] - r.d[0] * e2[2];
    float pz = r.d[0] * e2[1] - r.d[1] * e2[0];
    float det = e1[0] * px + e1[1] * py + e1[2] * pz;
    if (det == 0.0f) return false;
    float invDet = 1.0f / det;
    float tx = r.o[0] - v0[0], ty = r.o[1] - v0[1], tz = r.o[2] - v0[2];
    u = (tx * px + ty * py + tz * pz) * invDet;
    if (u < 0.0f || u > 1.0f) return false;
    float qx = ty * e1[2] - tz * e1[1];
    float qy = tz * e1[0] - tx * e1[2];
    float qz = tx * e1[1] - ty * e1[0];
    v = (r.d[0] * qx + r.d[1] * qy + r.d[2] * qz) * invDet;
    if (v < 0.0f || u + v > 1.0f) return false;
    t = (e2[0] * qx + e2[1] * qy + e2[2] * qz) * invDet;
    return t >= r.mint && t <= maxt;
}

namespace {
/// Edge functions in double precision: the products of floats are exact, so the sign is right
/// even when the float evaluation cancels to zero (Woop et al. 2013, section 4).
void edgeFunctionsDouble(float ax, float ay, float bx, float by, float cx, float cy, float &U, float &V, float &W) {
    U = float(double(cx) * double(by) - double(cy) * double(bx));
    V = float(double(ax) * double(cy) - double(ay) * double(cx));
    W = float(double(bx) * double(ay) - double(by) * double(ax));
}
} // namespace

bool intersectWatertight(const TriangleRay &r, const float p0[3], const float p1[3], const float p2[3], float maxt,
                         float &t, float &u, float &v) {
    // Vertices relative to the origin, then sheared so that the ray is the +z axis.
    float az0 = p0[r.kz] - r.o[r.kz], bz0 = p1[r.kz] - r.o[r.kz], cz0 = p2[r.kz] - r.o[r.kz];
    float ax = (p0[r.kx] - r.o[r.kx]) - r.sx * az0, ay = (p0[r.ky] - r.o[r.ky]) - r.sy * az0;
    float bx = (p1[r.kx] - r.o[r.kx]) - r.sx * bz0, by = (p1[r.ky] - r.o[r.ky]) - r.sy * bz0;
    float cx = (p2[r.kx] - r.o[r.kx]) - r.sx * cz0, cy = (p2[r.ky] - r.o[r.ky]) - r.sy * cz0;
    // Scaled barycentrics: U weighs p0, V weighs p1, W weighs p2.
    float U = cx * by - cy * bx;
    float V = ax * cy - ay * cx;
    float W = bx * ay - by * ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f) edgeFunctionsDouble(ax, ay, bx, by, cx, cy, U, V, W);
    // Both windings are hits: the three must not have mixed signs.
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return false;
    float det = U + V + W;
    if (det == 0.0f) return false;
    float T = U * (r.sz * az0) + V * (r.sz * bz0) + W * (r.sz * cz0);
    float invDet = 1.0f / det;
    t = T * invDet;
    if (!(t >= r.mint && t <= maxt)) return false;
    u = V * invDet;
    v = W * invDet;
    return true;
}

// ---------------------------------------------------------------------------------------------

void TriangleStore::reset(Intersector kind, size_t refs) {
    m_kind = kind;
    m_data.assign(9 * refs, 0.0f);
    m_data.shrink_to_fit();
    m_prims.assign(refs, 0u);
    m_prims.shrink_to_fit();
}

void TriangleStore::setLeaf(uint32_t begin, const uint32_t *prims, uint32_t n,
                            const std::vector<std::array<Point3f, 3>> &vertices) {
    float *rows = m_data.data() + size_t(9) * begin;
    for (uint32_t i = 0; i < n; ++i) {
        const std::array<Point3f, 3> &p = vertices[prims[i]];
        m_prims[begin + i] = prims[i];
        for (int c = 0; c < 3; ++c) {
            rows[(0 + c) * n + i] = p[0][c];
            if (m_kind == Intersector::MT) {
                rows[(3 + c) * n + i] = p[1][c] - p[0][c];
                rows[(6 + c) * n + i] = p[2][c] - p[0][c];
            } else {
                rows[(3 + c) * n + i] = p[1][c];
                rows[(6 + c) * n + i] = p[2][c];
            }
        }
    }
}

namespace {
/// Load triangle i of a leaf whose rows have stride n.
inline void loadCorner(const float *rows, uint32_t n, uint32_t i, int first, float out[3]) {
    out[0] = rows[(first + 0) * n + i];
    out[1] = rows[(first + 1) * n + i];
    out[2] = rows[(first + 2) * n + i];
}
} // namespace

bool TriangleStore::intersect(const TriangleRay &ray, uint32_t begin, uint32_t n, Hit &best) const {
    const float *rows = m_data.data() + size_t(9) * begin;
    const uint32_t *prims = m_prims.data() + begin;
    bool found = false;
    for (uint32_t i = 0; i < n; ++i) {
        float a[3], b[3], c[3], t, u, v;
        loadCorner(rows, n, i, 0, a);
        loadCorner(rows, n, i, 3, b);
        loadCorner(rows, n, i, 6, c);
        bool hit = m_kind == Intersector::MT ? intersectMT(ray, a, b, c, best.t, t, u, v)
                                             : intersectWatertight(ray, a, b, c, best.t, t, u, v);
        if (hit && (t < best.t || prims[i] < best.prim)) {
            best = Hit{t, u, v, prims[i]};
            found = true;
        }
    }
    return found;
}

bool TriangleStore::occluded(const TriangleRay &ray, uint32_t begin, uint32_t n, float maxt) const {
    const float *rows = m_data.data() + size_t(9) * begin;
    for (uint32_t i = 0; i < n; ++i) {
        float a[3], b[3], c[3], t, u, v;
        loadCorner(rows, n, i, 0, a);
        loadCorner(rows, n, i, 3, b);
        loadCorner(rows, n, i, 6, c);
        bool hit = m_kind == Intersector::MT ? intersectMT(ray, a, b, c, maxt, t, u, v)
                                             : intersectWatertight(ray, a, b, c, maxt, t, u, v);
        if (hit) return true;
    }
    return false;
}

} // namespace nori
