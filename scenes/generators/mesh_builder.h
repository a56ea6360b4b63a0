/// \file mesh_builder.h
/// \brief Accumulates triangles for the generators, welding bit-identical vertices so that
/// pieces built separately (cube-sphere faces, adjoining boxes) share their corners.
#pragma once

#include <nori/mesh.h>
#include <functional>
#include <unordered_map>

namespace nori::gen {

/// \brief Builds one MeshData from boxes, grids, spheres and loose triangles.
class MeshBuilder {
public:
    /// \brief Index of the vertex at \p p (an existing one if bit-identical, -0 == +0).
    uint32_t vertex(const Point3f &p);
    void triangle(uint32_t a, uint32_t b, uint32_t c);
    void triangle(const Point3f &a, const Point3f &b, const Point3f &c);
    /// \brief Two triangles (a, b, c) and (a, c, d).
    void quad(const Point3f &a, const Point3f &b, const Point3f &c, const Point3f &d);
    /// \brief Axis-aligned box with outward winding (12 triangles; 10 without the bottom).
    void box(const Point3f &lo, const Point3f &hi, bool bottom = true);
    /// \brief (nu + 1) x (nv + 1) points f(i, j) joined into 2 nu nv triangles.
    void grid(int nu, int nv, const std::function<Point3f(int, int)> &f);
    /// \brief Closed sphere-like surface: the six faces of a cube, n x n quads each, every
    /// point mapped by \p f from its unit direction (12 n^2 triangles, no poles, no slivers).
    void cubeSphere(int n, const std::function<Point3f(const Vector3f &)> &f);
    /// \brief Sphere of \p radius around \p center (12 n^2 triangles).
    void sphere(const Point3f &center, float radius, int n);
    /// \brief Closed cylinder along +y: \p segments side quads, both caps as fans.
    void cylinder(const Point3f &baseCenter, float radius, float height, int segments);
    /// \brief Open tapered tube from \p from (radius \p r0) to \p to (radius \p r1):
    /// \p segments side quads, no caps. Straight chains of tubes along one axis weld.
    void tube(const Point3f &from, const Point3f &to, float r0, float r1, int segments);

    uint64_t triangleCount() const { return m_data.faces.size(); }
    /// \brief The mesh so far; the builder is empty afterwards.
    MeshData take();

private:
    struct KeyHash {
        size_t operator()(const std::array<uint32_t, 3> &k) const {
            uint64_t h = (uint64_t(k[0]) * 0x9e3779b97f4a7c15ull) ^ (uint64_t(k[1]) * 0xc2b2ae3d27d4eb4full) ^
                         (uint64_t(k[2]) * 0x165667b19e3779f9ull);
            return size_t(h ^ (h >> 29));
        }
    };
    MeshData m_data;
    std::unordered_map<std::array<uint32_t, 3>, uint32_t, KeyHash> m_index;
};

} // namespace nori::gen
