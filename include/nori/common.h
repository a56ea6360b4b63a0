/// \file common.h
/// \brief Basic types, constants and the project's exception type.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <fmt/format.h>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

namespace nori {

/// \brief Thin aliases over Eigen: the names say what a value means.
using Vector2f = Eigen::Vector2f;
using Vector3f = Eigen::Vector3f;
using Vector3d = Eigen::Vector3d;
using Point2f = Eigen::Vector2f;
using Point3f = Eigen::Vector3f;
using Normal3f = Eigen::Vector3f;
using Point2i = Eigen::Vector2i;
using Vector2i = Eigen::Vector2i;
using Matrix4f = Eigen::Matrix4f;

constexpr float Pi = 3.14159265358979323846f;
constexpr float InvPi = 0.31830988618379067154f;
constexpr float InvTwoPi = 0.15915494309189533577f;
constexpr float InvFourPi = 0.07957747154594766788f;
constexpr float Infinity = std::numeric_limits<float>::infinity();

/// \brief Every user-facing error: the message is complete ("FILE:LINE: what is wrong").
class NoriException : public std::runtime_error {
public:
    explicit NoriException(const std::string &message) : std::runtime_error(message) {}
    template <typename... Args>
    explicit NoriException(fmt::format_string<Args...> format, Args &&...args)
        : std::runtime_error(fmt::format(format, std::forward<Args>(args)...)) {}
};

/// \brief \p text as an error message may echo it: control characters become '?' (the message
/// stays one line, no escape sequence reaches the terminal) and more than \p maxBytes bytes are
/// cut at a UTF-8 character boundary, with an ellipsis.
inline std::string shown(std::string_view text, size_t maxBytes = 60) {
    size_t cut = text.size();
    if (cut > maxBytes) {
        cut = maxBytes;
        while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
    }
    std::string out(text.substr(0, cut));
    for (char &c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return cut < text.size() ? out + "\u2026" : out;
}

/// \brief Degrees to radians.
inline float degToRad(float deg) { return deg * (Pi / 180.0f); }

/// \brief Clamp \p value into [lo, hi].
template <typename T> inline T clamp(T value, T lo, T hi) {
    return value < lo ? lo : (value > hi ? hi : value);
}

/// \brief Make an arbitrary orthonormal frame (s, t) around the unit vector \p n.
/// Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
inline void coordinateSystem(const Vector3f &n, Vector3f &s, Vector3f &t) {
    float sign = std::copysign(1.0f, n.z());
    float a = -1.0f / (sign + n.z());
    float b = n.x() * n.y() * a;
    s = Vector3f(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
    t = Vector3f(b, sign + n.y() * n.y() * a, -n.y());
}

} // namespace nori
