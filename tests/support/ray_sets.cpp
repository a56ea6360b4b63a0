/// \file ray_sets.cpp
/// \brief Deterministic ray sets shared by the oracle tests and the benchmark (implementation).
#include "ray_sets.h"
#include <algorithm>
#include <pcg_random.hpp>

namespace nori {

namespace {
/// Uniform float in [0, 1) from the top 24 bits of a 32-bit draw.
float uniform(pcg32 &rng) { return float(rng() >> 8) * 0x1p-24f; }

/// Malley's method: cosine-weighted direction around +z.
Vector3f cosineHemisphere(float u1, float u2) {
    float r = std::sqrt(u1), phi = 2.0f * Pi * u2;
    return Vector3f(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1)));
}

/// Surface points (offset towards the viewer) and normals facing the viewer, for primary hits.
void primaryHits(const std::vector<Ray3f> &primary, const ClosestHitFunction &hitFunction, const MeshTable &table,
                 std::vector<Point3f> &points, std::vector<Normal3f> &normals, std::vector<uint32_t> *prims = nullptr) {
    for (const Ray3f &ray : primary) {
        Hit hit;
        if (!hitFunction(ray, hit)) continue;
        Point3f p;
        Normal3f n;
        float offset;
        table.surface(hit.prim, hit.u, hit.v, p, n, offset);
        if (n.isZero()) continue;  // degenerate triangle: no meaningful bounce
        if (n.dot(ray.d) > 0.0f) n = -n;
        points.push_back(offsetRayOrigin(p, offset, n, -ray.d));
        normals.push_back(n);
        if (prims) prims->push_back(hit.prim);
    }
}
} // namespace

MeshTable::MeshTable(const std::vector<const Mesh *> &meshes) : m_meshes(meshes) {
    for (const Mesh *m : meshes) m_offsets.push_back(m_offsets.back() + m->triangleCount());
}

void MeshTable::surface(uint32_t prim, float u, float v, Point3f &p, Normal3f &n, float &offset) const {
    size_t idx = size_t(std::upper_bound(m_offsets.begin(), m_offsets.end(), prim) - m_offsets.begin()) - 1;
    const Mesh *mesh = m_meshes[idx];
    uint32_t f = prim - m_offsets[idx];
    const Point3f &p0 = mesh->vertex(f, 0), &p1 = mesh->vertex(f, 1), &p2 = mesh->vertex(f, 2);
    p = (1.0f - u - v) * p0 + u * p1 + v * p2;
    n = mesh->geometricNormal(f);
    offset = spawnOffset(p0, p1, p2, p, interpolationError(p0, p1, p2, 1.0f - u - v, u, v), n);
}

BoundingBox3f MeshTable::bbox() const {
    BoundingBox3f b;
    for (const Mesh *m : m_meshes) b.expandBy(m->bbox());
    return b;
}

std::unique_ptr<Camera> framingCamera(const BoundingBox3f &bbox, int width, int height) {
    const float fov = 30.0f;
    Point3f center = bbox.center();
    float radius = 0.5f * bbox.extents().norm();
    if (!(radius > 0.0f)) radius = 1.0f;
    // Far enough that the bounding sphere fits the narrower field of view.
    float aspect = float(width) / float(height);
    float halfFov = degToRad(0.5f * fov) * std::min(1.0f, 1.0f / aspect);
    float distance = 1.05f * radius / std::sin(halfFov);
    Vector3f viewDir = Vector3f(0.55f, 0.35f, 0.75f).normalized();
    PropertyList props;
    props.setLocation("<framing camera>");
    props.setInteger("width", width);
    props.setInteger("height", height);
    props.setFloat("fov", fov);
    props.setFloat("nearClip", 1e-3f * distance);
    props.setFloat("farClip", 1e3f * distance);
    props.setTransform("toWorld", Transform::lookAt(center + distance * viewDir, center, Vector3f(0, 1, 0)));
    std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(NoriObject::ECamera, "perspective", props);
    return std::unique_ptr<Camera>(static_cast<Camera *>(object.release()));
}

std::vector<Ray3f> cameraRays(const Camera &camera, int spp, uint64_t seed) {
    pcg32 rng(seed);
    const Vector2i size = camera.outputSize();
    std::vector<Ray3f> rays;
    rays.reserve(size_t(size.x()) * size.y() * spp);
    for (int y = 0; y < size.y(); ++y)
        for (int x = 0; x < size.x(); ++x)
            for (int s = 0; s < spp; ++s) {
                Ray3f ray;
                camera.sampleRay(ray, Point2f(x + uniform(rng), y + uniform(rng)), Point2f(0.5f, 0.5f));
                rays.push_back(ray);
            }
    return rays;
}

std::vector<Ray3f> randomBoxRays(const BoundingBox3f &bbox, size_t count, uint64_t seed) {
    pcg32 rng(seed);
    Vector3f grow = 0.25f * bbox.extents();
    Point3f lo = bbox.min - grow;
    Vector3f span = bbox.extents() + 2.0f * grow;
    auto randomPoint = [&] {
        return Point3f(lo.x() + span.x() * uniform(rng), lo.y() + span.y() * uniform(rng),
                       lo.z() + span.z() * uniform(rng));
    };
    std::vector<Ray3f> rays;
    rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        Point3f a = randomPoint(), b = randomPoint();
        if (a == b) continue;
        rays.emplace_back(a, b - a, 0.0f, (i & 1) ? 1.0f : Infinity);
    }
    return rays;
}

std::vector<Ray3f> diffuseRays(const std::vector<Ray3f> &primary, const ClosestHitFunction &hitFunction,
                               const MeshTable &table, uint64_t seed, std::vector<uint32_t> *sources) {
    std::vector<Point3f> points;
    std::vector<Normal3f> normals;
    if (sources) sources->clear();
    primaryHits(primary, hitFunction, table, points, normals, sources);
    pcg32 rng(seed);
    std::vector<Ray3f> rays;
    rays.reserve(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        Frame frame(normals[i]);
        float u1 = uniform(rng), u2 = uniform(rng);
        rays.emplace_back(points[i], frame.toWorld(cosineHemisphere(u1, u2)));
    }
    return rays;
}

std::vector<Ray3f> lightShadowRays(const std::vector<Ray3f> &primary, const ClosestHitFunction &hitFunction,
                                   const MeshTable &table, const Point3f &light, std::vector<uint32_t> *sources) {
    std::vector<Point3f> points;
    std::vector<Normal3f> normals;
    if (sources) sources->clear();
    primaryHits(primary, hitFunction, table, points, normals, sources);
    std::vector<Ray3f> rays;
    rays.reserve(points.size());
    for (const Point3f &p : points) rays.emplace_back(p, light - p, 0.0f, 1.0f);
    return rays;
}

std::vector<Ray3f> surfaceShadowRays(const std::vector<Ray3f> &primary, const ClosestHitFunction &hitFunction,
                                     const MeshTable &table, size_t count, uint64_t seed) {
    std::vector<Point3f> points;
    std::vector<Normal3f> normals;
    primaryHits(primary, hitFunction, table, points, normals);
    std::vector<Ray3f> rays;
    if (points.size() < 2) return rays;
    pcg32 rng(seed);
    rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const Point3f &a = points[rng(uint32_t(points.size()))];
        const Point3f &b = points[rng(uint32_t(points.size()))];
        if (a == b) continue;
        rays.emplace_back(a, b - a, 0.0f, 1.0f);
    }
    return rays;
}

Point3f lightAbove(const BoundingBox3f &bbox) {
    Vector3f e = bbox.extents();
    return bbox.center() + Vector3f(0.3f * e.x(), 1.5f * e.maxCoeff(), 0.4f * e.z());
}

} // namespace nori
