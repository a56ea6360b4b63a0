/// \file transform.h
/// \brief Homogeneous 4x4 transformation with its inverse.
#pragma once

#include <nori/ray.h>

namespace nori {

/// \brief An affine or projective transform and its cached inverse.
class Transform {
public:
    Transform() : m_matrix(Matrix4f::Identity()), m_inverse(Matrix4f::Identity()) {}
    /// \brief From a matrix; the inverse is computed (throws NoriException if singular).
    explicit Transform(const Matrix4f &matrix);

    /// \brief Finite, with a finite inverse, and not (nearly) singular. The test is relative
    /// and scale-aware: for an affine map only its linear part counts (a translation by 1e8 is
    /// fine), compared with the product of its column lengths, so uniform scaling does not matter.
    bool isInvertible() const;
    /// \brief isInvertible() for a matrix.
    static bool isWellConditioned(const Matrix4f &matrix);
    Transform(const Matrix4f &matrix, const Matrix4f &inverse) : m_matrix(matrix), m_inverse(inverse) {}

    const Matrix4f &matrix() const { return m_matrix; }
    const Matrix4f &inverseMatrix() const { return m_inverse; }
    Transform inverse() const { return Transform(m_inverse, m_matrix); }
    /// \brief this * other: \p other is applied first.
    Transform operator*(const Transform &other) const {
        return Transform(m_matrix * other.m_matrix, other.m_inverse * m_inverse);
    }

    Point3f applyPoint(const Point3f &p) const {
        Eigen::Vector4f r = m_matrix * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
        return r.head<3>() / r.w();
    }
    Vector3f applyVector(const Vector3f &v) const { return m_matrix.topLeftCorner<3, 3>() * v; }
    /// \brief Normals transform with the inverse transpose (not normalised).
    Normal3f applyNormal(const Normal3f &n) const { return m_inverse.topLeftCorner<3, 3>().transpose() * n; }
    Ray3f applyRay(const Ray3f &r) const { return Ray3f(applyPoint(r.o), applyVector(r.d), r.mint, r.maxt); }

    /// \brief Building blocks used by the XML <transform> element.
    static Transform translate(const Vector3f &delta);
    static Transform scale(const Vector3f &factors);
    static Transform rotate(const Vector3f &axis, float angleDegrees);
    /// \brief Camera-to-world for a camera at \p origin looking at \p target.
    static Transform lookAt(const Point3f &origin, const Point3f &target, const Vector3f &up);

    std::string toString() const;

private:
    Matrix4f m_matrix;
    Matrix4f m_inverse;
};

} // namespace nori
