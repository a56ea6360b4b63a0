/// \file triangle_box.h
/// \brief Exact triangle/box overlap by separating axes (Akenine-Möller 2001, "Fast 3D
/// Triangle-Box Overlap Testing").
#pragma once

#include <nori/bbox.h>

namespace nori {

/// \brief Does the triangle (a, b, c) touch the closed box \p box? Evaluated in double
/// precision on a box grown by a relative 2^-20 of its size, so rounding can only add
/// triangles, never drop one that touches (the octree must stay conservative).
/// Degenerate triangles (zero area, repeated corners) are handled: their missing axes are
/// simply never separating.
bool triangleOverlapsBox(const Point3f &a, const Point3f &b, const Point3f &c, const BoundingBox3f &box);
/// \brief The same answer for a triangle whose axisAlignedPlane() is \p plane, known to a
/// caller that tests the triangle against several boxes: an axis-aligned triangle (a wall, a
/// floor) needs a third of the separating axes.
bool triangleOverlapsBox(const Point3f &a, const Point3f &b, const Point3f &c, const BoundingBox3f &box, int plane);
/// \brief The axis i whose coordinate the corners share exactly (the triangle lies in the plane
/// x_i = const; the lowest such i), or -1.
inline int axisAlignedPlane(const Point3f &a, const Point3f &b, const Point3f &c) {
    return a.x() == b.x() && a.x() == c.x()   ? 0
           : a.y() == b.y() && a.y() == c.y() ? 1
           : a.z() == b.z() && a.z() == c.z() ? 2
                                              : -1;
}

} // namespace nori
