/// \file frame.h
/// \brief Orthonormal frame (s, t, n) for shading computations.
#pragma once

#include <nori/common.h>

namespace nori {

/// \brief Right-handed orthonormal basis; local z is the normal.
struct Frame {
    Vector3f s, t;
    Normal3f n;

    Frame() = default;
    /// \brief A frame around the unit normal \p normal.
    explicit Frame(const Normal3f &normal) : n(normal) { coordinateSystem(n, s, t); }

    Vector3f toLocal(const Vector3f &v) const { return Vector3f(v.dot(s), v.dot(t), v.dot(n)); }
    Vector3f toWorld(const Vector3f &v) const { return s * v.x() + t * v.y() + n * v.z(); }
    static float cosTheta(const Vector3f &v) { return v.z(); }
};

} // namespace nori
