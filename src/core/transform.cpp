/// \file transform.cpp
/// \brief Homogeneous 4x4 transformation with its inverse (implementation).
#include <nori/transform.h>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <sstream>

namespace nori {

bool Transform::isWellConditioned(const Matrix4f &matrix) {
    if (!matrix.allFinite()) return false;
    const Eigen::Matrix4d m = matrix.cast<double>();
    const bool affine = m.row(3) == Eigen::RowVector4d(0, 0, 0, 1);
    // |det| against Hadamard's bound (the product of the column lengths): 1 for orthogonal
    // columns, 0 for dependent ones, whatever the scale or the translation.
    auto relativeDet = [](const auto &a) {
        double bound = 1.0;
        for (int c = 0; c < a.cols(); ++c) bound *= a.col(c).norm();
        return bound > 0.0 && std::isfinite(bound) ? std::abs(a.determinant()) / bound : 0.0;
    };
    const double ratio = affine ? relativeDet(m.topLeftCorner<3, 3>()) : relativeDet(m);
    return ratio > 1e-7;  // float data: columns independent beyond float rounding
}

bool Transform::isInvertible() const { return isWellConditioned(m_matrix) && m_inverse.allFinite(); }

Transform::Transform(const Matrix4f &matrix) : m_matrix(matrix) {
    if (!isWellConditioned(matrix)) throw NoriException("transform matrix is singular or not finite");
    Eigen::FullPivLU<Eigen::Matrix4d> lu(matrix.cast<double>());
    m_inverse = lu.inverse().cast<float>();
    if (!m_inverse.allFinite()) throw NoriException("transform matrix is singular or not finite");
}

Transform Transform::translate(const Vector3f &delta) {
    Matrix4f m = Matrix4f::Identity();
    m.topRightCorner<3, 1>() = delta;
    Matrix4f inv = Matrix4f::Identity();
    inv.topRightCorner<3, 1>() = -delta;
    return Transform(m, inv);
}

Transform Transform::scale(const Vector3f &factors) {
    if ((factors.array() == 0.0f).any() || !factors.allFinite())
        throw NoriException("scale factors must be finite and non-zero");
    Matrix4f m = Matrix4f::Identity(), inv = Matrix4f::Identity();
    for (int i = 0; i < 3; ++i) {
        m(i, i) = factors[i];
        inv(i, i) = 1.0f / factors[i];
    }
    return Transform(m, inv);
}

Transform Transform::rotate(const Vector3f &axis, float angleDegrees) {
    if (!axis.allFinite() || axis.norm() == 0.0f || !std::isfinite(angleDegrees))
        throw NoriException("rotation needs a finite, non-zero axis and a finite angle");
    Matrix4f m = Matrix4f::Identity();
    m.topLeftCorner<3, 3>() = Eigen::AngleAxisf(degToRad(angleDegrees), axis.normalized()).toRotationMatrix();
    Matrix4f inv = Matrix4f::Identity();
    inv.topLeftCorner<3, 3>() = m.topLeftCorner<3, 3>().transpose();
    return Transform(m, inv);
}

Transform Transform::lookAt(const Point3f &origin, const Point3f &target, const Vector3f &up) {
    Vector3f dir = target - origin;
    if (!origin.allFinite() || !target.allFinite() || !up.allFinite() || !dir.allFinite() || dir.isZero(0.0f))
        throw NoriException("lookat needs distinct, finite origin and target");
    // |dir|^2 underflows for a scene 1e-30 across and overflows for one 1e37 across, though
    // their directions are well defined: there, Eigen's stableNormalized (which scales first);
    // elsewhere the plain division, so that every camera ray keeps its bits.
    auto unit = [](const Vector3f &v) {
        const float n2 = v.squaredNorm();
        return n2 >= std::numeric_limits<float>::min() && n2 <= std::numeric_limits<float>::max() ? v.normalized()
                                                                                                    : v.stableNormalized();
    };
    dir = unit(dir);
    if (up.isZero(0.0f)) throw NoriException("lookat 'up' vector is zero");
    Vector3f left = unit(up).cross(dir);
    if (!(left.norm() > 1e-6f)) throw NoriException("lookat 'up' vector is parallel to the view direction");
    left.normalize();
    Vector3f newUp = dir.cross(left);
    // Columns assigned one by one: the comma initializer with vector blocks trips a false
    // -Warray-bounds in GCC 12 when Eigen vectorises it with SSE only.
    Matrix4f m = Matrix4f::Identity();
    m.block<3, 1>(0, 0) = left;
    m.block<3, 1>(0, 1) = newUp;
    m.block<3, 1>(0, 2) = dir;
    m.block<3, 1>(0, 3) = origin;
    return Transform(m);
}

std::string Transform::toString() const {
    std::ostringstream os;
    os << m_matrix.format(Eigen::IOFormat(4, 0, ", ", ";\n", "", "", "[", "]"));
    return os.str();
}

} // namespace nori
