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

/// \brief One triangle prepared for the separating-axis test against several boxes (an octree
/// node's child cells): its edges, its normal and the nine edge axes do not depend on the box,
/// so they are computed once here instead of once per box. overlaps() gives
/// triangleOverlapsBox()'s answer (which is this test, made for one box).
class TriangleBoxTest {
public:
    /// \p plane: axisAlignedPlane(a, b, c).
    TriangleBoxTest(const Point3f &a, const Point3f &b, const Point3f &c, int plane);
    /// \brief Does the triangle touch the closed box \p box (grown as triangleOverlapsBox says)?
    bool overlaps(const BoundingBox3f &box) const;

private:
    typedef double D4 __attribute__((vector_size(32)));
    double m_v[3][3];  ///< the corners, in double
    /// The edge axes unit(i) x edge j and the normal as triangleOverlapsBox() tests them: for
    /// each edge j, lanes i = 0..2 are unit(i) x edge j, lane 3 the normal; x, y, z their
    /// components, ax, ay, az those components' magnitudes.
    D4 m_x[3], m_y[3], m_z[3], m_ax[3], m_ay[3], m_az[3];
    int m_plane;
};
/// \brief The axis i whose coordinate the corners share exactly (the triangle lies in the plane
/// x_i = const; the lowest such i), or -1.
inline int axisAlignedPlane(const Point3f &a, const Point3f &b, const Point3f &c) {
    return a.x() == b.x() && a.x() == c.x()   ? 0
           : a.y() == b.y() && a.y() == c.y() ? 1
           : a.z() == b.z() && a.z() == c.z() ? 2
                                              : -1;
}

} // namespace nori
