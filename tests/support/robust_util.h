/// \file robust_util.h
/// \brief Helpers of the stability and pathological-input tests: closed meshes generated in
/// code, accelerators made through the factory, and a double-precision reference intersector.
#pragma once

#include <gtest/gtest.h>
#include <nori/accel.h>
#include <nori/object.h>

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace nori::robust {

// ---------------------------------------------------------------------------------------
// Closed meshes with shared vertices (every edge is used by exactly two triangles).

/// Icosahedron subdivided \p levels times, vertices projected onto the unit sphere.
inline MeshData icosphere(int levels) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    MeshData m;
    for (auto p : {Point3f(-1, t, 0), Point3f(1, t, 0), Point3f(-1, -t, 0), Point3f(1, -t, 0),
                   Point3f(0, -1, t), Point3f(0, 1, t), Point3f(0, -1, -t), Point3f(0, 1, -t),
                   Point3f(t, 0, -1), Point3f(t, 0, 1), Point3f(-t, 0, -1), Point3f(-t, 0, 1)})
        m.positions.push_back(p.normalized());
    m.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
               {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        // One midpoint per edge, shared by both triangles of the edge.
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
            return midpoints[key] = uint32_t(m.positions.size() - 1);
        };
        std::vector<std::array<uint32_t, 3>> faces;
        for (auto f : m.faces) {
            uint32_t a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
            faces.push_back({f[0], a, c});
            faces.push_back({f[1], b, a});
            faces.push_back({f[2], c, b});
            faces.push_back({a, b, c});
        }
        m.faces = std::move(faces);
    }
    return m;
}

/// Torus around the y axis: major radius \p R, minor radius \p r, a \p nu x \p nv grid that wraps.
inline MeshData torus(float R, float r, int nu, int nv) {
    MeshData m;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            float u = 2.0f * Pi * float(i) / float(nu), v = 2.0f * Pi * float(j) / float(nv);
            float ring = R + r * std::cos(v);
            m.positions.emplace_back(ring * std::cos(u), r * std::sin(v), ring * std::sin(u));
        }
    auto id = [&](int i, int j) { return uint32_t(((i + nu) % nu) * nv + (j + nv) % nv); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return m;
}

/// The cube [-1, 1]^3, each face an \p n x \p n grid of quads (two triangles each); vertices
/// on the cube's edges and corners are shared between faces.
inline MeshData cube(int n) {
    MeshData m;
    std::map<std::array<int, 3>, uint32_t> index;  // integer grid coordinates in [0, n]^3
    auto vertex = [&](std::array<int, 3> g) {
        auto it = index.find(g);
        if (it != index.end()) return it->second;
        m.positions.emplace_back(-1.0f + 2.0f * float(g[0]) / float(n), -1.0f + 2.0f * float(g[1]) / float(n),
                                 -1.0f + 2.0f * float(g[2]) / float(n));
        return index[g] = uint32_t(m.positions.size() - 1);
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side <= 1; ++side) {
            int a = (axis + 1) % 3, b = (axis + 2) % 3;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    auto at = [&](int di, int dj) {
                        std::array<int, 3> g{};
                        g[axis] = side * n;
                        g[a] = i + di;
                        g[b] = j + dj;
                        return vertex(g);
                    };
                    uint32_t v00 = at(0, 0), v10 = at(1, 0), v11 = at(1, 1), v01 = at(0, 1);
                    // Orientation does not matter to intersection; alternate the diagonal for variety.
                    if ((i + j) % 2) {
                        m.faces.push_back({v00, v10, v11});
                        m.faces.push_back({v00, v11, v01});
                    } else {
                        m.faces.push_back({v00, v10, v01});
                        m.faces.push_back({v10, v11, v01});
                    }
                }
        }
    return m;
}

/// \p data with every position mapped to offset + scale * p (in float, like a scene's toWorld).
inline MeshData scaled(MeshData data, float scale, const Vector3f &offset) {
    for (Point3f &p : data.positions) p = offset + scale * p;
    return data;
}

// ---------------------------------------------------------------------------------------
// Accelerators through the factory.

inline bool octreeAvailable() { return NoriObjectFactory::isRegistered(NoriObject::EAccel, "octree"); }

/// An accel of \p type with \p props over \p meshes, built. Returns nullptr when the accel
/// ignores one of \p props (e.g. an `intersector` that this branch does not support yet).
inline std::unique_ptr<Accel> makeAccel(const std::string &type, const PropertyList &props,
                                        const std::vector<const Mesh *> &meshes) {
    std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(NoriObject::EAccel, type, props);
    if (!props.unusedProperties().empty()) return nullptr;
    std::unique_ptr<Accel> accel(static_cast<Accel *>(object.release()));
    accel->activate();
    for (const Mesh *mesh : meshes) accel->addMesh(mesh);
    accel->build();
    return accel;
}

/// Properties selecting the intersector \p name ("" for the accel's default).
inline PropertyList intersectorProps(const std::string &name) {
    PropertyList props;
    props.setLocation("test");
    if (!name.empty()) props.setString("intersector", name, "test");
    return props;
}

/// The value of statistic \p name, if the accel reports it.
inline std::optional<double> stat(const Accel &accel, const std::string &name) {
    for (const AccelStat &s : accel.statistics())
        if (s.name == name) return s.value;
    return std::nullopt;
}

// ---------------------------------------------------------------------------------------
// Reference: every triangle in double precision, with a margin saying how clear-cut a hit
// or miss is (so tests compare only rays whose answer float rounding cannot flip).

struct RefHit {
    bool hit = false;
    double t = 0.0;
    uint32_t prim = ~0u;
    double margin = 1e300;  ///< smallest |barycentric| or t-distance that decided any triangle near the answer
};

/// Ray/triangle in double: returns t, and sets the signed barycentric margin (min of b0, b1, b2).
inline bool rayTriangleDouble(const Vector3d &o, const Vector3d &d, const Vector3d &p0, const Vector3d &p1,
                              const Vector3d &p2, double &t, double &minBary) {
    Vector3d e1 = p1 - p0, e2 = p2 - p0, n = e1.cross(e2);
    double denom = n.dot(d);
    double area2 = n.norm();
    if (area2 == 0.0 || std::abs(denom) <= 1e-12 * area2 * d.norm()) return false;  // degenerate or parallel
    t = n.dot(p0 - o) / denom;
    Vector3d x = o + t * d;
    // Barycentrics from sub-triangle areas, normalised by the full area.
    double b0 = (p1 - x).cross(p2 - x).dot(n) / (area2 * area2);
    double b1 = (p2 - x).cross(p0 - x).dot(n) / (area2 * area2);
    double b2 = 1.0 - b0 - b1;
    minBary = std::min({b0, b1, b2});
    return true;
}

/// Closest hit over all triangles of \p meshes (global numbering like Accel), in double.
/// The margin is the smallest distance of the decision of any triangle from flipping: the
/// barycentric margin of triangles crossed within [mint, maxt], and the relative distance
/// of t to mint / maxt for triangles the ray passes through.
inline RefHit referenceHit(const std::vector<const Mesh *> &meshes, const Ray3f &ray) {
    RefHit best;
    best.t = std::numeric_limits<double>::infinity();
    Vector3d o = ray.o.cast<double>(), d = ray.d.cast<double>();
    const double tmin = ray.mint, tmax = ray.maxt;
    uint32_t offset = 0;
    for (const Mesh *mesh : meshes) {
        for (uint32_t f = 0; f < mesh->triangleCount(); ++f) {
            double t, minBary;
            if (!rayTriangleDouble(o, d, mesh->vertex(f, 0).cast<double>(), mesh->vertex(f, 1).cast<double>(),
                                   mesh->vertex(f, 2).cast<double>(), t, minBary))
                continue;
            const bool inside = minBary >= 0.0, inRange = t >= tmin && t <= tmax;
            if (inside) {
                double scale = std::max({std::abs(t), std::abs(tmin), 1e-30});
                double tMargin = std::min(std::abs(t - tmin), std::isinf(tmax) ? 1e300 : std::abs(t - tmax)) / scale;
                best.margin = std::min(best.margin, tMargin);
            }
            if (inRange) best.margin = std::min(best.margin, std::abs(minBary));
            if (inside && inRange && t < best.t) {
                best.t = t;
                best.prim = offset + f;
                best.hit = true;
            }
        }
        offset += mesh->triangleCount();
    }
    return best;
}

} // namespace nori::robust
