/// \file mesh_measures.h
/// \brief Measures of a generated mesh that the generator tests check: its bounds, a
/// triangle's bounds and a triangle's area (in double).
#pragma once

#include <nori/bbox.h>
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

} // namespace nori::gen::test
