/// \file mesh_builder.cpp
/// \brief MeshBuilder: welded vertices and the primitive pieces the generators share.
#include "mesh_builder.h"
#include <cstring>

namespace nori::gen {

uint32_t MeshBuilder::vertex(const Point3f &p) {
    std::array<uint32_t, 3> key;
    for (int k = 0; k < 3; ++k) {
        float x = p[k] + 0.0f;  // -0 becomes +0, so both weld
        std::memcpy(&key[size_t(k)], &x, sizeof x);
    }
    auto [it, inserted] = m_index.emplace(key, uint32_t(m_data.positions.size()));
    if (inserted) m_data.positions.push_back(p + Point3f::Zero());
    return it->second;
}

void MeshBuilder::triangle(uint32_t a, uint32_t b, uint32_t c) { m_data.faces.push_back({a, b, c}); }

void MeshBuilder::triangle(const Point3f &a, const Point3f &b, const Point3f &c) {
    triangle(vertex(a), vertex(b), vertex(c));
}

void MeshBuilder::quad(const Point3f &a, const Point3f &b, const Point3f &c, const Point3f &d) {
    uint32_t ia = vertex(a), ib = vertex(b), ic = vertex(c), id = vertex(d);
    triangle(ia, ib, ic);
    triangle(ia, ic, id);
}

void MeshBuilder::box(const Point3f &lo, const Point3f &hi, bool bottom) {
    auto p = [&](int x, int y, int z) { return Point3f(x ? hi.x() : lo.x(), y ? hi.y() : lo.y(), z ? hi.z() : lo.z()); };
    // Counter-clockwise seen from outside.
    quad(p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0));  // +y
    if (bottom) quad(p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1));  // -y
    quad(p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1));  // +x
    quad(p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0));  // -x
    quad(p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1));  // +z
    quad(p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0));  // -z
}

void MeshBuilder::grid(int nu, int nv, const std::function<Point3f(int, int)> &f) {
    std::vector<uint32_t> index(size_t(nu + 1) * size_t(nv + 1));
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) index[size_t(j) * size_t(nu + 1) + size_t(i)] = vertex(f(i, j));
    auto at = [&](int i, int j) { return index[size_t(j) * size_t(nu + 1) + size_t(i)]; };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            // Alternate the diagonal so a flat grid has no preferred direction.
            if ((i + j) & 1) {
                triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
                triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
            } else {
                triangle(at(i, j), at(i + 1, j), at(i, j + 1));
                triangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            }
        }
}

void MeshBuilder::cubeSphere(int n, const std::function<Point3f(const Vector3f &)> &f) {
    // Face k has normal axis a = k / 2 and sign s; (u, v) run over the other two axes in an
    // order that keeps the winding outward. Cube coordinates -1 + 2 i / n are exact at the
    // seams, so both faces of a seam produce bit-identical points and the welding closes it.
    for (int k = 0; k < 6; ++k) {
        int a = k / 2, b = (a + 1) % 3, c = (a + 2) % 3;
        float s = (k & 1) ? -1.0f : 1.0f;
        grid(n, n, [&](int i, int j) {
            Vector3f q;
            q[a] = s;
            q[b] = -1.0f + 2.0f * float(s > 0 ? i : n - i) / float(n);
            q[c] = -1.0f + 2.0f * float(j) / float(n);
            return f(q.normalized());
        });
    }
}

void MeshBuilder::sphere(const Point3f &center, float radius, int n) {
    cubeSphere(n, [&](const Vector3f &d) { return Point3f(center + radius * d); });
}

void MeshBuilder::cylinder(const Point3f &baseCenter, float radius, float height, int segments) {
    auto ring = [&](int i, float y) {
        float phi = 2.0f * Pi * float(i % segments) / float(segments);
        return Point3f(baseCenter.x() + radius * std::cos(phi), baseCenter.y() + y,
                       baseCenter.z() + radius * std::sin(phi));
    };
    Point3f top = baseCenter + Vector3f(0, height, 0);
    for (int i = 0; i < segments; ++i) {
        quad(ring(i, 0), ring(i, height), ring(i + 1, height), ring(i + 1, 0));
        triangle(top, ring(i + 1, height), ring(i, height));
        triangle(baseCenter, ring(i, 0), ring(i + 1, 0));
    }
}

void MeshBuilder::tube(const Point3f &from, const Point3f &to, float r0, float r1, int segments) {
    Vector3f axis = (to - from).normalized();
    // Any frame around the axis will do; it depends on the axis alone, so two tubes that
    // continue one another along the same axis produce the same ring between them.
    Vector3f helper = std::abs(axis.y()) < 0.9f ? Vector3f(0, 1, 0) : Vector3f(1, 0, 0);
    Vector3f u = axis.cross(helper).normalized(), v = axis.cross(u);
    auto ring = [&](const Point3f &c, float r, int i) {
        float phi = 2.0f * Pi * float(i % segments) / float(segments);
        return Point3f(c + r * (std::cos(phi) * u + std::sin(phi) * v));
    };
    for (int i = 0; i < segments; ++i) quad(ring(from, r0, i), ring(from, r0, i + 1), ring(to, r1, i + 1), ring(to, r1, i));
}

MeshData MeshBuilder::take() {
    MeshData out = std::move(m_data);
    m_data = MeshData();
    m_index.clear();
    return out;
}

} // namespace nori::gen
