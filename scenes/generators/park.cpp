/// \file park.cpp
/// \brief "park": trees drawn as crossed cards (two vertical quads through one axis, the way
/// foliage is often modelled for speed) on a lawn, the whole scene inside a sky dome: a UV
/// sphere 25 times the lawn's size, whose poles are fans of slivers around one vertex.
/// The camera stands inside, so every ray ends somewhere. What it stresses: large quads that
/// cross one another along a line (no midplane separates a tree's two cards), and a closed
/// shell whose faces are all far away and whose fans no subdivision splits.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <algorithm>
#include <cmath>

namespace nori::gen {

namespace {
const float Lawn = 400.0f;    // half the lawn's side
const float Dome = 10000.0f;  // the sky's radius
}

GeneratedScene generatePark(const GenParams &params) {
    MeshBuilder b;
    // The sky: a UV sphere of nu x nv quads (nu = 2 nv), about a seventh of the budget. Row 0
    // and row nv are the poles, one vertex each: the first and last rows of quads are fans.
    const int nv = std::max(8, int(std::lround(std::sqrt(0.15 * double(params.triangles) / 4.0)))), nu = 2 * nv;
    auto sky = [&](int i, int j) {
        if (j == 0) return Point3f(0.0f, Dome, 0.0f);
        if (j == nv) return Point3f(0.0f, -Dome, 0.0f);
        const float theta = Pi * float(j) / float(nv), phi = 2.0f * Pi * float(i % nu) / float(nu);
        return Point3f(Dome * std::sin(theta) * std::cos(phi), Dome * std::cos(theta), Dome * std::sin(theta) * std::sin(phi));
    };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const Point3f a = sky(i, j), c = sky(i + 1, j + 1);
            if (j > 0) b.triangle(a, sky(i + 1, j), c);
            if (j < nv - 1) b.triangle(a, c, sky(i, j + 1));
        }
    // The lawn.
    b.quad(Point3f(-Lawn, 0, -Lawn), Point3f(-Lawn, 0, Lawn), Point3f(Lawn, 0, Lawn), Point3f(Lawn, 0, -Lawn));
    // The trees: two cards each, crossed at right angles along their common vertical axis.
    GenRandom rng(params.seed, 23);
    const uint64_t used = b.triangleCount();
    const uint64_t trees = params.triangles > used + 4 ? (params.triangles - used) / 4 : 1;
    for (uint64_t k = 0; k < trees; ++k) {
        const float x = rng.range(-0.9f * Lawn, 0.9f * Lawn), z = rng.range(-0.9f * Lawn, 0.9f * Lawn);
        const float height = rng.range(2.0f, 8.0f), half = rng.range(0.25f, 0.45f) * height;
        const float turn = rng.range(0.0f, 0.5f * Pi);
        for (int card = 0; card < 2; ++card) {
            const float angle = turn + 0.5f * Pi * float(card);
            const float dx = half * std::cos(angle), dz = half * std::sin(angle);
            b.quad(Point3f(x - dx, 0, z - dz), Point3f(x + dx, 0, z + dz), Point3f(x + dx, height, z + dz),
                   Point3f(x - dx, height, z - dz));
        }
    }
    GeneratedScene s;
    s.shape = "park";
    s.description = "crossed-card trees on a lawn under a sky dome with polar fans, camera inside";
    s.mesh = b.take();
    // At eye height at the lawn's edge, looking across the trees and up into the sky.
    s.camera.origin = Point3f(0.0f, 1.7f, -0.95f * Lawn);
    s.camera.target = Point3f(0.0f, 0.1f * Lawn, 0.0f);
    s.camera.fov = 60.0f;
    s.camera.nearClip = 0.01f;
    s.camera.farClip = 10.0f * Dome;
    s.aoLength = 4.0f;
    return s;
}

} // namespace nori::gen
