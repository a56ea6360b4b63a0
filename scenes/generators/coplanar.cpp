/// \file coplanar.cpp
/// \brief "coplanar": faces lying on the octree's split planes. The bounds are exactly
/// [-1, 1]^3, so cells split at 0, +-0.5, +-0.25, ...; the scene has the three planes through
/// the origin twice each (two different tessellations overlapping), stacked cubes of side
/// 0.25 whose shared faces lie back to back on those planes, cubes touching only along
/// edges, and quads on two faces of the bounds.
#include "shape_generators.h"
#include "mesh_builder.h"
#include <cmath>

namespace nori::gen {

namespace {
/// The square [-1, 1]^2 in the plane x[axis] = \p offset, tessellated n x n.
void planeSquare(MeshBuilder &b, int axis, float offset, int n) {
    b.grid(n, n, [&](int i, int j) {
        Point3f p;
        p[axis] = offset;
        p[(axis + 1) % 3] = -1.0f + 2.0f * float(i) / float(n);
        p[(axis + 2) % 3] = -1.0f + 2.0f * float(j) / float(n);
        return p;
    });
}

/// Cube [lo, lo + size]^3 with each face tessellated n x n (outward winding).
void tessellatedCube(MeshBuilder &b, const Point3f &lo, float size, int n) {
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            if (side == 0) std::swap(u, v);  // flip the winding on the low face
            b.grid(n, n, [&](int i, int j) {
                Point3f p = lo;
                p[axis] += float(side) * size;
                p[u] += size * float(i) / float(n);
                p[v] += size * float(j) / float(n);
                return p;
            });
        }
}
} // namespace

GeneratedScene generateCoplanar(const GenParams &params) {
    MeshBuilder b;
    for (int axis = 0; axis < 3; ++axis) {
        planeSquare(b, axis, 0.0f, 16);
        planeSquare(b, axis, 0.0f, 11);  // overlaps the first, triangles crossing differently
    }
    // Two faces of the bounds: the floor y = -1 and the back wall z = -1.
    planeSquare(b, 1, -1.0f, 1);
    planeSquare(b, 2, -1.0f, 1);
    // Cubes of side 0.25: a staircase corner in the +++ octant (face-sharing neighbours) and
    // a checkerboard in the --- octant (neighbours touch along edges only).
    std::vector<Point3f> cubes;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
                if (i + j + k < 4) cubes.emplace_back(0.25f * float(i), 0.25f * float(j), 0.25f * float(k));
                if ((i + j + k) % 2 == 0) cubes.emplace_back(-1.0f + 0.25f * float(i), -1.0f + 0.25f * float(j),
                                                             -1.0f + 0.25f * float(k));
            }
    uint64_t left = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
    int n = std::max(1, int(std::lround(std::sqrt(double(left) / double(cubes.size() * 12)))));
    for (const Point3f &lo : cubes) tessellatedCube(b, lo, 0.25f, n);
    GeneratedScene s;
    s.shape = "coplanar";
    s.description = "overlapping coplanar faces and stacked cubes on the split planes of [-1, 1]^3";
    s.mesh = b.take();
    s.camera.origin = Point3f(2.6f, 2.1f, 3.3f);
    s.camera.target = Point3f(0.0f, 0.0f, 0.0f);
    s.camera.fov = 45.0f;
    s.aoLength = 0.25f;
    return s;
}

} // namespace nori::gen
