/// \file studio.cpp
/// \brief Pedestal, cyclorama and light panels of the default scene.
#include "studio.h"

namespace mkscene {

namespace {

// A segment of a profile in the (radius, y) half-plane, traversed clockwise around the
// solid, revolved about the y axis with its own row of vertices.
void revolveSegment(MeshBuilder &m, double r0, double y0, double r1, double y1, int steps, int ns) {
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

} // namespace

void buildPedestal(MeshBuilder &m, double radius, double height, double bevel, int ns) {
    revolveSegment(m, 0.0, 0.0, radius - bevel, 0.0, 12, ns);                    // top
    revolveSegment(m, radius - bevel, 0.0, radius, -bevel, 1, ns);               // bevel
    revolveSegment(m, radius, -bevel, radius, -height + bevel, 2, ns);           // side
    revolveSegment(m, radius, -height + bevel, radius - bevel, -height, 1, ns);  // lower bevel
    revolveSegment(m, radius - bevel, -height, 0.0, -height, 6, ns);            // bottom
}

void buildCyclorama(MeshBuilder &m, double floorY, double zFront, double zBack, double cove, double top,
                    double halfWidth, int coveSteps) {
    // The profile in (z, y), from the front edge of the floor to the top of the wall.
    std::vector<std::pair<double, double>> profile;
    profile.push_back({zFront, floorY});
    for (int k = 0; k <= coveSteps; ++k) {
        double a = 0.5 * kPi * k / coveSteps;  // 0: on the floor, pi/2: on the wall
        profile.push_back({zBack + cove - cove * std::sin(a), floorY + cove - cove * std::cos(a)});
    }
    profile.push_back({zBack, top});
    const uint32_t base = uint32_t(m.pos.size());
    for (const auto &[z, y] : profile) {
        m.add({-halfWidth, y, z});
        m.add({halfWidth, y, z});
    }
    // Along the profile (front to back, then up) x along +x faces up and forward.
    for (size_t k = 0; k + 1 < profile.size(); ++k) {
        uint32_t a = base + uint32_t(2 * k);
        m.quad(a, a + 2, a + 1, a + 3);
    }
}

void buildPanel(MeshBuilder &m, V3 centre, V3 target, double width, double height) {
    V3 n = normalize(target - centre);
    // Long side horizontal; a panel facing straight down gets its long side along x.
    V3 right = cross(V3{0, 1, 0}, n);
    right = dot(right, right) > 1e-12 ? normalize(right) : V3{1, 0, 0};
    V3 up = cross(n, right);
    V3 hw = (0.5 * width) * right, hh = (0.5 * height) * up;
    uint32_t a = m.add(centre - hw - hh), b = m.add(centre + hw - hh);
    uint32_t c = m.add(centre - hw + hh), d = m.add(centre + hw + hh);
    // With "up" as quad()'s first direction, its front side is right x up = n.
    m.quad(a, c, b, d);
}

} // namespace mkscene
