/// \file accel.cpp
/// \brief Ray-intersection acceleration structure interface (closest hit and any hit) (implementation).
#include <nori/accel.h>
#include <algorithm>
#include <chrono>
#include <nori/cpu_clock.h>

namespace nori {

void Accel::addMesh(const Mesh *mesh) {
    uint64_t total = uint64_t(m_offsets.back()) + mesh->triangleCount();
    if (total >= uint64_t(UINT32_MAX)) throw NoriException("{}: too many triangles in the scene", mesh->location());
    BoundingBox3f box = m_bbox;
    box.expandBy(mesh->bbox());
    // Cells, boxes and their areas are computed in float: a side beyond its range (corners past
    // +-1.7e38) would make them infinite and their midpoints NaN.
    if (box.isValid() && !box.extents().allFinite())
        throw NoriException("{}: the scene spans more than the float range ({} to {}); scale it down",
                            mesh->location(), box.min.minCoeff(), box.max.maxCoeff());
    m_meshes.push_back(mesh);
    m_offsets.push_back(uint32_t(total));
    m_bbox = box;
}

void Accel::build() {
    const double cpuStart = threadCpuMilliseconds();
    auto start = std::chrono::steady_clock::now();
    buildImpl();
    m_buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    m_buildCpuMs = threadCpuMilliseconds() - cpuStart;
}

std::pair<const Mesh *, uint32_t> Accel::locate(uint32_t prim) const {
    // m_offsets is sorted; the mesh is the last one whose offset is <= prim.
    size_t idx = size_t(std::upper_bound(m_offsets.begin(), m_offsets.end(), prim) - m_offsets.begin()) - 1;
    return {m_meshes[idx], prim - m_offsets[idx]};
}

bool Accel::rayIntersect(const Ray3f &ray, Intersection &its, bool shadowRay) const {
    if (shadowRay) return occluded(ray);
    Hit hit;
    if (!intersect(ray, hit)) return false;
    completeIntersection(ray, hit, its);
    return true;
}

void Accel::completeIntersection(const Ray3f &ray, const Hit &hit, Intersection &its) const {
    auto [mesh, f] = locate(hit.prim);
    its.mesh = mesh;
    its.triIndex = f;
    its.t = hit.t;
    const auto &face = mesh->faces()[f];
    float b0 = 1.0f - hit.u - hit.v, b1 = hit.u, b2 = hit.v;
    const auto &P = mesh->positions();
    its.p = b0 * P[face[0]] + b1 * P[face[1]] + b2 * P[face[2]];
    Vector3f pError = interpolationError(P[face[0]], P[face[1]], P[face[2]], b0, b1, b2);
    if (mesh->hasUVs()) {
        const auto &UV = mesh->uvs();
        its.uv = b0 * UV[face[0]] + b1 * UV[face[1]] + b2 * UV[face[2]];
    } else {
        its.uv = Point2f(b1, b2);
    }
    Vector3f cross = (P[face[1]] - P[face[0]]).cross(P[face[2]] - P[face[0]]);
    float twiceArea = cross.norm();
    Normal3f ng = twiceArea > 0.0f ? Normal3f(cross / twiceArea) : Normal3f(-ray.d.normalized());  // degenerate: face the ray
    its.geoFrame = Frame(ng);
    its.offset = spawnOffset(P[face[0]], P[face[1]], P[face[2]], its.p, pError, ng, twiceArea);
    if (mesh->hasNormals()) {
        const auto &N = mesh->normals();
        Normal3f ns = b0 * N[face[0]] + b1 * N[face[1]] + b2 * N[face[2]];
        float len = ns.norm();
        its.shFrame = len > 0.0f && std::isfinite(len) ? Frame(Normal3f(ns / len)) : its.geoFrame;
    } else {
        its.shFrame = its.geoFrame;
    }
}

std::vector<AccelStat> Accel::statistics() const {
    return {{"build_ms", m_buildMs, false}, {"triangles", double(triangleCount()), true}};
}

} // namespace nori
