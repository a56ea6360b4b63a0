// nori-mkscene: writes the default scene's mesh (a decorated trefoil-knot tube
// resting above a round bevelled pedestal) as an OBJ file with smooth normals.
//
//   nori-mkscene OUT.obj
//
// The output is deterministic for a given build, and the file is written atomically
// (nori::AtomicFile), so a failed or interrupted run never leaves a truncated mesh
// behind for the renderer.

#include <app/cli_app.h>
#include <nori/atomic_file.h>
#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

struct V3 {
    double x = 0, y = 0, z = 0;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 normalize(V3 a) {
    double l = std::sqrt(dot(a, a));
    return l > 0 ? (1.0 / l) * a : V3{0, 1, 0};
}

struct Mesh {
    std::vector<V3> pos;
    std::vector<std::array<uint32_t, 3>> tri;

    uint32_t add(V3 p) {
        pos.push_back(p);
        return uint32_t(pos.size() - 1);
    }
    // Quad a-b-d-c, where b follows a along the first grid direction and c follows a
    // along the second; the winding makes (c-a)x(b-a) the front side. Triangles that
    // collapse (apex rows of a revolved profile) are skipped.
    void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
        if (a != c && a != b && b != c) tri.push_back({a, c, b});
        if (b != c && c != d && b != d) tri.push_back({b, c, d});
    }
};

// ---------------------------------------------------------------------------
// Knot: a (p,q) torus knot whose plane is horizontal (y up).
constexpr int kP = 2, kQ = 3;          // trefoil
constexpr double kMajor = 1.0;         // torus radius
constexpr double kMinor = 0.5;         // winding radius around the torus core
constexpr double kTube = 0.30;         // tube radius before relief
// Strands come no closer than ~0.83 and the curve's radius of curvature stays
// above ~0.71 with these radii, so a tube of radius <= 0.35 cannot self-intersect.

V3 knotCurve(double t) {
    double w = kMajor + kMinor * std::cos(kQ * t);
    return {w * std::cos(kP * t), kMinor * std::sin(kQ * t), w * std::sin(kP * t)};
}
V3 knotTangent(double t) {
    double w = kMajor + kMinor * std::cos(kQ * t);
    double dw = -kQ * kMinor * std::sin(kQ * t);
    return normalize({dw * std::cos(kP * t) - kP * w * std::sin(kP * t), kQ * kMinor * std::cos(kQ * t),
                      dw * std::sin(kP * t) + kP * w * std::cos(kP * t)});
}

// Relief on the tube: kRidges raised ridges spiralling kTwist full turns around the
// tube over one loop, with a row of beads in each groove. kRidges * kTwist must be an
// integer so the pattern closes seamlessly where the loop meets itself.
constexpr int kRidges = 8, kTwist = 2, kBeads = 72;
double relief(double u, double theta) {
    double phase = kRidges * (theta - 2.0 * kPi * kTwist * u);
    double ridge = std::pow(0.5 + 0.5 * std::cos(phase), 3.0);
    double groove = std::pow(0.5 - 0.5 * std::cos(phase), 6.0);
    double bead = std::pow(0.5 + 0.5 * std::cos(2.0 * kPi * kBeads * u), 4.0);
    return 1.0 + 0.16 * ridge + 0.14 * groove * bead;
}

// Closed tube of nu rings x nv vertices per ring.
void buildKnot(Mesh &m, int nu, int nv) {
    std::vector<V3> c(nu), t(nu), n(nu);
    for (int i = 0; i < nu; ++i) {
        double s = 2.0 * kPi * i / nu;
        c[i] = knotCurve(s);
        t[i] = knotTangent(s);
    }
    // Rotation-minimising frame by double reflection, so the tube does not twist
    // (a Frenet frame would flip at inflections).
    n[0] = normalize(cross(t[0], V3{0, 1, 0}));
    auto transport = [&](int i, int j, V3 r) {
        V3 v1 = c[j] - c[i];
        double c1 = dot(v1, v1);
        V3 rl = r - (2.0 / c1 * dot(v1, r)) * v1;
        V3 tl = t[i] - (2.0 / c1 * dot(v1, t[i])) * v1;
        V3 v2 = t[j] - tl;
        double c2 = dot(v2, v2);
        return c2 > 0 ? rl - (2.0 / c2 * dot(v2, rl)) * v2 : rl;
    };
    for (int i = 0; i + 1 < nu; ++i) n[i + 1] = normalize(transport(i, i + 1, n[i]));
    // The frame comes back rotated by some holonomy angle; spread its correction
    // evenly along the loop so the last ring lines up with the first.
    V3 back = normalize(transport(nu - 1, 0, n[nu - 1]));
    double holonomy = std::atan2(dot(cross(n[0], back), t[0]), dot(n[0], back));

    uint32_t base = uint32_t(m.pos.size());
    for (int i = 0; i < nu; ++i) {
        double u = double(i) / nu;
        double a = -holonomy * u;
        V3 b0 = cross(t[i], n[i]);
        V3 nn = std::cos(a) * n[i] + std::sin(a) * b0;
        V3 bb = cross(t[i], nn);
        for (int j = 0; j < nv; ++j) {
            double th = 2.0 * kPi * j / nv;
            V3 d = std::cos(th) * nn + std::sin(th) * bb;
            m.add(c[i] + (kTube * relief(u, th)) * d);
        }
    }
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            uint32_t i1 = (i + 1) % nu, j1 = (j + 1) % nv;
            // With d = cos*n + sin*(t x n), (next ring) x (next around) points inward,
            // so quad() gets the rings as its first direction to face outward.
            m.quad(base + i * nv + j, base + i1 * nv + j, base + i * nv + j1, base + i1 * nv + j1);
        }
}

// ---------------------------------------------------------------------------
// Pedestal: a profile in the (radius, y) half-plane, traversed clockwise around the
// solid, revolved about the y axis. Every profile segment gets its own vertices so
// that the creases between cap, bevel and side stay sharp under smooth normals.
void revolveSegment(Mesh &m, double r0, double y0, double r1, double y1, int steps, int ns) {
    std::vector<uint32_t> prev, cur;
    for (int k = 0; k <= steps; ++k) {
        double f = double(k) / steps;
        double r = r0 + (r1 - r0) * f, y = y0 + (y1 - y0) * f;
        cur.clear();
        if (r <= 0.0) {
            cur.assign(ns, m.add({0, y, 0}));  // apex: one shared vertex
        } else {
            for (int s = 0; s < ns; ++s) {
                double ph = 2.0 * kPi * s / ns;
                cur.push_back(m.add({r * std::cos(ph), y, r * std::sin(ph)}));
            }
        }
        if (k > 0)
            for (int s = 0; s < ns; ++s) {
                int s1 = (s + 1) % ns;
                m.quad(prev[s], cur[s], prev[s1], cur[s1]);
            }
        prev.swap(cur);
    }
}

void buildPedestal(Mesh &m, double radius, double height, double bevel, int ns) {
    revolveSegment(m, 0.0, 0.0, radius - bevel, 0.0, 12, ns);                    // top
    revolveSegment(m, radius - bevel, 0.0, radius, -bevel, 1, ns);               // bevel
    revolveSegment(m, radius, -bevel, radius, -height + bevel, 2, ns);           // side
    revolveSegment(m, radius, -height + bevel, radius - bevel, -height, 1, ns);  // lower bevel
    revolveSegment(m, radius - bevel, -height, 0.0, -height, 6, ns);            // bottom
}

// Area-weighted vertex normals (the cross product's length is twice the area).
std::vector<V3> vertexNormals(const Mesh &m) {
    std::vector<V3> n(m.pos.size());
    for (const auto &f : m.tri) {
        V3 fn = cross(m.pos[f[1]] - m.pos[f[0]], m.pos[f[2]] - m.pos[f[0]]);
        for (uint32_t v : f) n[v] = n[v] + fn;
    }
    for (V3 &v : n) v = normalize(v);
    return n;
}

// ---------------------------------------------------------------------------
// Output: everything is formatted into one buffer and written with a single fwrite.
struct Writer {
    std::string buf;
    char tmp[64];
    void text(const char *s) { buf.append(s); }
    void real(double v) {
        // Shortest round-trip form of the float the renderer will read back.
        auto r = std::to_chars(tmp, tmp + sizeof(tmp), float(v));
        buf.push_back(' ');
        buf.append(tmp, r.ptr);
    }
    void index(uint32_t i, bool withNormal) {
        auto r = std::to_chars(tmp, tmp + sizeof(tmp), i + 1);  // OBJ indices are 1-based
        buf.push_back(' ');
        buf.append(tmp, r.ptr);
        if (withNormal) {
            buf.append("//");
            buf.append(tmp, r.ptr);
        }
    }
};

}  // namespace

int main(int argc, char **argv) {
    nori::CliApp cli("nori-mkscene", "Writes the default scene's mesh as an OBJ file with smooth normals.");
    std::string outPath;
    cli.app().add_option("output", outPath, "the OBJ file to write")->required()->option_text("OUT.obj");
    if (std::optional<int> status = cli.parse(argc, argv)) return *status;

    Mesh m;
    // 1040 rings x 144 around gives roughly square quads along the ~16-unit-long,
    // 1.9-unit-round tube and ~300k triangles in total.
    buildKnot(m, 1040, 144);
    const uint32_t knotEnd = uint32_t(m.pos.size());

    // Scale the knot to a 1-unit footprint and let it hover just above the pedestal
    // top (y = 0), close enough for contact shadows in the AO render.
    double extent = 0, ymin = 1e30;
    for (uint32_t i = 0; i < knotEnd; ++i) {
        extent = std::max({extent, std::fabs(m.pos[i].x), std::fabs(m.pos[i].z)});
        ymin = std::min(ymin, m.pos[i].y);
    }
    double scale = 0.5 / extent;
    const double gap = 0.012;
    for (uint32_t i = 0; i < knotEnd; ++i) {
        V3 &p = m.pos[i];
        p = {p.x * scale, (p.y - ymin) * scale + gap, p.z * scale};
    }

    buildPedestal(m, 0.62, 0.07, 0.012, 192);

    std::vector<V3> nrm = vertexNormals(m);

    Writer w;
    w.buf.reserve(m.pos.size() * 64 + m.tri.size() * 40 + 256);
    w.text("# nori-mkscene: trefoil knot tube with spiral ridges and beads on a bevelled pedestal\n");
    for (const V3 &p : m.pos) {
        w.text("v");
        w.real(p.x), w.real(p.y), w.real(p.z);
        w.text("\n");
    }
    for (const V3 &n : nrm) {
        w.text("vn");
        w.real(n.x), w.real(n.y), w.real(n.z);
        w.text("\n");
    }
    for (const auto &f : m.tri) {
        w.text("f");
        for (uint32_t v : f) w.index(v, true);
        w.text("\n");
    }
    try {
        nori::AtomicFile::write(outPath, w.buf);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "nori-mkscene: %s\n", nori::oneLine(e.what()).c_str());
        return 1;
    }
    std::printf("nori-mkscene: wrote %s (%zu vertices, %zu triangles)\n", outPath.c_str(), m.pos.size(), m.tri.size());
    return 0;
}
