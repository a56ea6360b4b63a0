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

} // namespace nori
