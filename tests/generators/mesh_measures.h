/// \file mesh_measures.h
/// \brief What the generator tests measure a generated mesh with: its bounds, a triangle's
/// bounds and area (in double), and a brute-force accelerator over it for the camera checks.
#pragma once

#include <nori/accel.h>
#include <nori/bbox.h>
#include <memory>
#include <scene_generator.h>

namespace nori::gen::test {

inline BoundingBox3f boundsOf(const MeshData &m) {
    BoundingBox3f b;
    for (const Point3f &p : m.positions) b.expandBy(p);
    return b;
}

inline BoundingBox3f triangleBounds(const MeshData &m, size_t f) {
    BoundingBox3f b;
    for (uint32_t i : m.faces[f]) b.expandBy(m.positions[i]);
    return b;
}

inline double area(const MeshData &m, size_t f) {
    const auto &i = m.faces[f];
    Vector3d a = m.positions[i[0]].cast<double>(), b = m.positions[i[1]].cast<double>(),
             c = m.positions[i[2]].cast<double>();
    return 0.5 * (b - a).cross(c - a).norm();
}

/// A built brute-force accelerator over \p mesh (which must outlive it).
inline std::unique_ptr<Accel> bruteForce(const Mesh &mesh) {
    PropertyList none;
    std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(NoriObject::EAccel, "brute", none);
    std::unique_ptr<Accel> accel(static_cast<Accel *>(object.release()));
    accel->addMesh(&mesh);
    accel->build();
    return accel;
}

} // namespace nori::gen::test
