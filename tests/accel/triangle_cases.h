/// \file triangle_cases.h
/// \brief Rays aimed at the vertices and edges of meshes (exactly, and a few ulps beside), each
/// with a leaf of 16 triangles around its target, for the ray/triangle decision tests.
#pragma once

#include "robust_util.h"

#include <accel/triangle.h>
#include <pcg_random.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace nori::decisions {

/// One ray and the leaf (16 triangles) it is tested against.
struct Case {
    Ray3f ray;
    Point3f target;  ///< the vertex or edge point aimed at (the ray passes within rounding of it)
    uint32_t leaf;
    std::string kind;     ///< "vertex", "edge", "near vertex", "near edge"
    bool sealed = false;  ///< aimed exactly at the target, and the triangles around it do not fold
                          ///< over in the ray's view: a watertight kernel must hit one of them
    std::vector<int> around;     ///< slots of the triangles that touch the target (2 for an edge)
    std::array<Point3f, 2> edge;  ///< an edge target's endpoints
};

struct CaseSet {
    std::string name;
    std::vector<std::array<Point3f, 3>> triangles;
    std::vector<std::array<uint32_t, 16>> leaves;  ///< triangle ids, slot by slot
    std::vector<Case> cases;

    static size_t offset(uint32_t leaf) { return size_t(leaf) * TriangleStore::leafWords(16); }
    const std::array<Point3f, 3> &triangle(uint32_t leaf, int slot) const { return triangles[leaves[leaf][size_t(slot)]]; }

    /// Every leaf written into one store (leaves of 16 keep their order: slot i is leaves[l][i]).
    TriangleStore store(Intersector kind) const {
        TriangleStore s;
        s.reset(kind, offset(uint32_t(leaves.size())));
        for (uint32_t l = 0; l < leaves.size(); ++l) s.setLeaf(offset(l), leaves[l].data(), 16, triangles);
        return s;
    }
};

/// \p p moved by \p ulps units in the last place along axis \p axis.
inline Point3f nudged(Point3f p, int axis, int ulps) {
    for (int i = 0; i < std::abs(ulps); ++i) p[axis] = std::nextafter(p[axis], ulps > 0 ? Infinity : -Infinity);
    return p;
}

/// Cases on a mesh (at least 16 triangles). Targets: every vertex, and points at fractions
/// 1/2 and 1/10 of every edge (computed in float, so they lie on the edge up to rounding).
/// Four rays per target: from inside[i] and from outside(target, i), exactly at the target and
/// one to three ulps beside it. \p sealedInside: rays from the inside points see no fold (true
/// for a convex mesh around them).
inline CaseSet meshCases(const std::string &name, const MeshData &m, const std::vector<Point3f> &inside,
                         const std::function<Point3f(const Point3f &, int)> &outside, bool sealedInside) {
    CaseSet set;
    set.name = name;
    std::vector<Point3f> centroids;
    for (const auto &f : m.faces) {
        set.triangles.push_back({m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]});
        centroids.push_back((m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]) / 3.0f);
    }
    struct Target {
        Point3f p;
        std::vector<uint32_t> around;
        bool isEdge;
        std::array<Point3f, 2> edge;
    };
    std::vector<Target> targets;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
    std::vector<std::vector<uint32_t>> fans(m.positions.size());
    for (uint32_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            fans[m.faces[f][k]].push_back(f);
            edges[std::minmax(m.faces[f][k], m.faces[f][(k + 1) % 3])].push_back(f);
        }
    for (uint32_t v = 0; v < m.positions.size(); ++v) targets.push_back({m.positions[v], fans[v], false, {}});
    for (const auto &[e, faces] : edges)
        for (float frac : {0.5f, 0.1f}) {
            const Point3f &a = m.positions[e.first], &b = m.positions[e.second];
            targets.push_back({a + frac * (b - a), faces, true, {a, b}});
        }
    for (size_t i = 0; i < targets.size(); ++i) {
        const Target &t = targets[i];
        // The triangles around the target, then the nearest others; rotated so that the
        // target's triangles visit every lane.
        std::vector<uint32_t> ids = t.around;
        std::vector<std::pair<float, uint32_t>> byDistance;
        for (uint32_t f = 0; f < centroids.size(); ++f)
            if (std::find(ids.begin(), ids.end(), f) == ids.end()) byDistance.push_back({(centroids[f] - t.p).squaredNorm(), f});
        std::partial_sort(byDistance.begin(), byDistance.begin() + (16 - ids.size()), byDistance.end());
        for (size_t k = 0; ids.size() < 16; ++k) ids.push_back(byDistance[k].second);
        std::array<uint32_t, 16> leaf;
        std::vector<int> around;
        for (int s = 0; s < 16; ++s) {
            const int slot = int((size_t(s) + i) % 16);
            leaf[size_t(slot)] = ids[size_t(s)];
            if (size_t(s) < t.around.size()) around.push_back(slot);
        }
        const uint32_t l = uint32_t(set.leaves.size());
        set.leaves.push_back(leaf);
        const std::string kind = t.isEdge ? "edge" : "vertex";
        const Point3f in = inside[i % inside.size()], out = outside(t.p, int(i));
        const int axis = int(i % 3), sign = i % 2 ? 1 : -1;
        const Point3f beside = nudged(t.p, axis, sign), farther = nudged(t.p, (axis + 1) % 3, 3 * sign);
        set.cases.push_back({Ray3f(in, t.p - in), t.p, l, kind, sealedInside, around, t.edge});
        set.cases.push_back({Ray3f(out, t.p - out), t.p, l, kind, false, around, t.edge});
        set.cases.push_back({Ray3f(in, beside - in), t.p, l, "near " + kind, false, around, t.edge});
        set.cases.push_back({Ray3f(out, farther - out), t.p, l, "near " + kind, false, around, t.edge});
    }
    return set;
}

/// A small deterministic perturbation.
inline Vector3f jitter(int k, float amount) {
    pcg32 rng(uint64_t(k) * 7919u + 1u);
    auto u = [&] { return (float(rng() >> 8) * 0x1p-24f - 0.5f) * 2.0f * amount; };
    return Vector3f(u(), u(), u());
}

/// Discs of 5-8 triangles around a centre, slightly bumpy, at scales 1e-3 .. 1e3 and offsets of
/// 100 times their size (so that coordinates use every bit of their mantissas): a height field
/// over its plane, seen from within 35 degrees of the plane's normal, never folds.
inline MeshData discs(int count, uint64_t seed) {
    pcg32 rng(seed);
    auto uniform = [&] { return float(rng() >> 8) * 0x1p-24f; };
    MeshData m;
    for (int k = 0; k < count; ++k) {
        const float scale = std::pow(10.0f, float(k % 7) - 3.0f);
        const Vector3f offset = 100.0f * scale * Vector3f(uniform() - 0.5f, uniform() - 0.5f, uniform() - 0.5f);
        const int spokes = 5 + k % 4;
        const uint32_t centre = uint32_t(m.positions.size());
        m.positions.push_back(offset + 0.05f * scale * Vector3f(0.0f, 0.0f, uniform() - 0.5f));
        float angle = 0.0f;
        for (int s = 0; s < spokes; ++s) {
            const float r = scale * (0.5f + uniform());
            m.positions.push_back(offset + Vector3f(r * std::cos(angle), r * std::sin(angle), 0.05f * scale * (uniform() - 0.5f)));
            angle += 2.0f * Pi / float(spokes) * (0.7f + 0.6f * uniform());
            if (s == spokes - 1) angle = 0.0f;
        }
        for (int s = 0; s < spokes; ++s)
            m.faces.push_back({centre, centre + 1 + uint32_t(s), centre + 1 + uint32_t((s + 1) % spokes)});
    }
    return m;
}

/// All case sets: closed meshes (convex ones seen from inside), a torus, bumpy discs.
inline std::vector<CaseSet> allCaseSets() {
    using robust::cube;
    using robust::icosphere;
    using robust::scaled;
    using robust::torus;
    std::vector<CaseSet> sets;
    const std::vector<Point3f> ball = {Point3f(0, 0, 0), Point3f(0.1f, -0.2f, 0.3f), Point3f(-0.5f, 0.25f, 0.125f)};
    auto away = [](const Point3f &p, int k) { return Point3f(3.0f * p + jitter(k, 0.3f)); };
    sets.push_back(meshCases("icosphere", icosphere(2), ball, away, true));
    {
        const Vector3f offset(1.0f, 2.0f, 3.0f);
        std::vector<Point3f> in;
        for (const Point3f &p : ball) in.push_back(offset + 1e-3f * p);
        auto awayScaled = [offset](const Point3f &p, int k) { return Point3f(offset + 3.0f * (p - offset) + 1e-3f * jitter(k, 0.3f)); };
        sets.push_back(meshCases("icosphere 1e-3 at (1,2,3)", scaled(icosphere(2), 1e-3f, offset), in, awayScaled, true));
    }
    // Axis-aligned faces on a grid: many edge functions are exactly zero.
    sets.push_back(meshCases("cube", cube(3), {Point3f(0, 0, 0), Point3f(0.5f, 0.5f, 0.5f), Point3f(0.3f, -0.7f, 0.1f)}, away, true));
    {
        std::vector<Point3f> core;
        for (int i = 0; i < 7; ++i) core.emplace_back(std::cos(0.9f * float(i)), 0.0f, std::sin(0.9f * float(i)));
        sets.push_back(meshCases("torus", torus(1.0f, 0.35f, 24, 12), core, away, false));
    }
    {
        // Discs: rays at the targets from above and below, within 25 degrees of the normal (z);
        // sealed at the centre vertex and the inner edges (the rim has one triangle only).
        MeshData d = discs(40, 11);
        CaseSet set = meshCases("discs", d, {Point3f(0, 0, 0)}, away, false);
        for (size_t i = 0; i < set.cases.size(); ++i) {
            Case &c = set.cases[i];
            if (c.kind.rfind("near", 0) == 0) continue;
            const auto &p = set.triangle(c.leaf, c.around[0]);
            const float size = (p[1] - p[0]).norm(), side = i % 2 ? 1.0f : -1.0f;
            const Vector3f tilt = jitter(int(i), 0.6f).cwiseProduct(Vector3f(1, 1, 0));
            const Point3f o = c.target + size * (Vector3f(0.0f, 0.0f, 2.0f * side) + tilt);
            c.ray = Ray3f(o, c.target - o);
            c.sealed = c.kind == "edge" ? c.around.size() == 2 : c.around.size() >= 5;
        }
        sets.push_back(std::move(set));
    }
    return sets;
}

} // namespace nori::decisions
