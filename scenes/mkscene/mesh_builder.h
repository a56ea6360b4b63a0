/// \file mesh_builder.h
/// \brief A triangle mesh under construction for nori-mkscene, and its OBJ output.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace mkscene {

constexpr double kPi = 3.14159265358979323846;

/// \brief A point or vector in double precision (the mesh is rounded to float only on output).
struct V3 {
    double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 normalize(V3 a) {
    double l = std::sqrt(dot(a, a));
    return l > 0 ? (1.0 / l) * a : V3{0, 1, 0};
}

/// \brief Vertices and triangles; written as OBJ with or without smooth vertex normals.
class MeshBuilder {
public:
    std::vector<V3> pos;
    std::vector<std::array<uint32_t, 3>> tri;

    uint32_t add(V3 p) {
        pos.push_back(p);
        return uint32_t(pos.size() - 1);
    }
    /// \brief Quad a-b-d-c, where b follows a along the first grid direction and c follows a
    /// along the second; the winding makes (c-a)x(b-a) the front side. Triangles that
    /// collapse (apex rows of a revolved profile) are skipped.
    void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
        if (a != c && a != b && b != c) tri.push_back({a, c, b});
        if (b != c && c != d && b != d) tri.push_back({b, c, d});
    }
    /// \brief Area-weighted vertex normals (each vertex averages the faces around it).
    std::vector<V3> vertexNormals() const;
    /// \brief Write \p path (OBJ; faces `f a//a ...` when \p withNormals) atomically
    /// (nori::AtomicFile), so a failed run never leaves a truncated mesh. Prints the reason
    /// on one line and returns false on failure.
    bool writeObj(const std::string &path, const std::string &comment, bool withNormals) const;
};

} // namespace mkscene
