/// \file city.cpp
/// \brief "city": axis-aligned boxes (buildings) on one ground quad, 120 x 8 x 120. Most
/// triangles are small and axis-aligned, the ground is two huge triangles, building floors
/// lie in the ground's plane, and the scene is 15x wider than tall.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <cmath>

namespace nori::gen {

GeneratedScene generateCity(const GenParams &params) {
    const float half = 60.0f, maxHeight = 8.0f;
    uint64_t boxes = std::max<uint64_t>(1, (params.triangles - 2) / 12);
    int lots = int(std::ceil(std::sqrt(double(boxes))));
    float lot = 2.0f * half / float(lots);
    GenRandom rng(params.seed, 1);
    MeshBuilder b;
    b.quad(Point3f(-half, 0, -half), Point3f(-half, 0, half), Point3f(half, 0, half), Point3f(half, 0, -half));
    for (uint64_t k = 0; k < boxes; ++k) {
        int i = int(k % uint64_t(lots)), j = int(k / uint64_t(lots));
        float sx = lot * rng.range(0.35f, 0.9f), sz = lot * rng.range(0.35f, 0.9f);
        float x = -half + lot * float(i) + rng.range(0.0f, lot - sx);
        float z = -half + lot * float(j) + rng.range(0.0f, lot - sz);
        // Mostly low buildings, a few towers; the first one reaches the full height.
        float u = rng.uniform();
        float h = k == 0 ? maxHeight : 0.3f + (maxHeight - 0.3f) * u * u * u;
        b.box(Point3f(x, 0, z), Point3f(x + sx, h, z + sz));
    }
    GeneratedScene s;
    s.shape = "city";
    s.description = "axis-aligned boxes on a ground quad, 120 x 8 x 120";
    s.mesh = b.take();
    s.camera.origin = Point3f(62, 38, 88);
    s.camera.target = Point3f(0, 0, 0);
    s.camera.fov = 50.0f;
    s.camera.nearClip = 0.01f;
    s.aoLength = 4.0f;
    return s;
}

} // namespace nori::gen
