/// \file tabletop.cpp
/// \brief "tabletop": a small table with tiny objects (centimetres) standing on a ground quad
/// 2000 units across, like Nori's table scene: the ground's two triangles span the whole
/// scene while everything the camera looks at fills a millionth of its bounds.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <cmath>

namespace nori::gen {

GeneratedScene generateTabletop(const GenParams &params) {
    const float ground = 1000.0f, top = 0.75f;
    GenRandom rng(params.seed, 9);
    MeshBuilder b;
    b.quad(Point3f(-ground, 0, -ground), Point3f(-ground, 0, ground), Point3f(ground, 0, ground),
           Point3f(ground, 0, -ground));
    b.box(Point3f(-0.6f, top - 0.04f, -0.4f), Point3f(0.6f, top, 0.4f));
    for (int sx : {-1, 1})
        for (int sz : {-1, 1})
            b.box(Point3f(0.52f * float(sx) - 0.03f, 0, 0.32f * float(sz) - 0.03f),
                  Point3f(0.52f * float(sx) + 0.03f, top - 0.04f, 0.32f * float(sz) + 0.03f));
    // Cups (cylinders) and balls; balls share the remaining budget.
    const int cups = 8, balls = 24, cupSegments = 48;
    for (int k = 0; k < cups; ++k) {
        float r = rng.range(0.02f, 0.045f);
        b.cylinder(Point3f(rng.range(-0.5f, 0.5f), top, rng.range(-0.32f, 0.32f)), r, rng.range(0.05f, 0.12f),
                   cupSegments);
    }
    uint64_t left = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
    int n = std::max(1, int(std::lround(std::sqrt(double(left / balls) / 12.0))));
    for (int k = 0; k < balls; ++k) {
        float r = rng.range(0.008f, 0.04f);
        b.sphere(Point3f(rng.range(-0.55f, 0.55f), top + r, rng.range(-0.35f, 0.35f)), r, n);
    }
    GeneratedScene s;
    s.shape = "tabletop";
    s.description = "small table with centimetre-sized objects on a 2000 x 2000 ground quad";
    s.mesh = b.take();
    s.camera.origin = Point3f(0.9f, 1.35f, 1.3f);
    s.camera.target = Point3f(0.0f, 0.7f, 0.0f);
    s.camera.fov = 45.0f;
    s.camera.nearClip = 1e-3f;
    s.aoLength = 0.15f;
    return s;
}

} // namespace nori::gen
