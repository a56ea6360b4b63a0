/// \file ray_sets.h
/// \brief Deterministic ray sets shared by the oracle tests and the benchmark.
#pragma once

#include <nori/accel.h>
#include <nori/camera.h>
#include <functional>
#include <memory>

namespace nori {

/// \brief Closest-hit query used to find surface points (normally the Embree oracle).
using ClosestHitFunction = std::function<bool(const Ray3f &, Hit &)>;

/// \brief Global triangle numbering over a list of meshes, as nori::Accel does it.
class MeshTable {
public:
    explicit MeshTable(const std::vector<const Mesh *> &meshes);
    /// \brief Point and unit geometric normal of global triangle \p prim at barycentrics (u, v), and
    /// the distance a ray leaving the point must start off the surface (nori::spawnOffset).
    void surface(uint32_t prim, float u, float v, Point3f &p, Normal3f &n, float &offset) const;
    BoundingBox3f bbox() const;
    uint32_t triangleCount() const { return m_offsets.back(); }
    const std::vector<const Mesh *> &meshes() const { return m_meshes; }

private:
    std::vector<const Mesh *> m_meshes;
    std::vector<uint32_t> m_offsets{0};
};

/// \brief A camera framing \p bbox from a three-quarter view (fov 30, horizontal).
std::unique_ptr<Camera> framingCamera(const BoundingBox3f &bbox, int width, int height);
/// \brief \p spp jittered rays per pixel, pixels in row-major order.
std::vector<Ray3f> cameraRays(const Camera &camera, int spp, uint64_t seed);
/// \brief Rays between two random points of \p bbox grown by 25% on each side; half of
/// them are segments (maxt = 1), half are infinite rays.
std::vector<Ray3f> randomBoxRays(const BoundingBox3f &bbox, size_t count, uint64_t seed);
/// \brief One cosine-weighted bounce ray (about the normal facing the ray) from each hit of \p primary.
/// \p sources, when given, receives the global triangle each ray leaves.
std::vector<Ray3f> diffuseRays(const std::vector<Ray3f> &primary, const ClosestHitFunction &hitFunction,
                               const MeshTable &table, uint64_t seed, std::vector<uint32_t> *sources = nullptr);
/// \brief Segments (maxt = 1) from each hit of \p primary towards \p light; \p sources as above.
std::vector<Ray3f> lightShadowRays(const std::vector<Ray3f> &primary, const ClosestHitFunction &hitFunction,
                                   const MeshTable &table, const Point3f &light,
                                   std::vector<uint32_t> *sources = nullptr);
/// \brief Segments (maxt = 1) between random pairs of the surface points hit by \p primary.
std::vector<Ray3f> surfaceShadowRays(const std::vector<Ray3f> &primary, const ClosestHitFunction &hitFunction,
                                     const MeshTable &table, size_t count, uint64_t seed);
/// \brief A point light position above the bounding box (used by the shadow ray sets).
Point3f lightAbove(const BoundingBox3f &bbox);

} // namespace nori
