/// \file wide.cpp
/// \brief "wide": a plain 1000 x 1000 whose whole height is 1: a gently rolling terrain grid
/// with clusters of small rocks sunk into it. Bounds 1000x wider than tall in two axes, so
/// cubic cells are either enormous or hopelessly many.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <cmath>

namespace nori::gen {

GeneratedScene generateWide(const GenParams &params) {
    const float half = 500.0f;
    const int rockN = 2;                 // 48 triangles per rock
    const uint64_t rockTriangles = 48;
    uint64_t terrainBudget = params.triangles / 2;
    int cells = std::max(1, int(std::sqrt(double(terrainBudget) / 2.0)));
    WaveNoise terrain(params.seed, 6, 16, 2.0f * Pi / 400.0f, 2.0f * Pi / 20.0f, 1.0f);
    auto height = [&](float x, float z) { return 0.3f + 0.3f * terrain(x, z); };  // [0, 0.6]
    MeshBuilder b;
    b.grid(cells, cells, [&](int i, int j) {
        float x = -half + 2.0f * half * float(i) / float(cells), z = -half + 2.0f * half * float(j) / float(cells);
        return Point3f(x, height(x, z), z);
    });
    // Rocks in clusters ("villages" on the plain); the first cluster is in front of the camera.
    GenRandom rng(params.seed, 7);
    uint64_t rocks = (params.triangles - b.triangleCount()) / rockTriangles;
    const uint64_t perCluster = 60;
    WaveNoise rockShape(params.seed, 8, 8, 2.0f, 8.0f, 1.0f);
    Point2f cluster(0.0f, 420.0f);
    for (uint64_t k = 0; k < rocks; ++k) {
        if (k > 0 && k % perCluster == 0) cluster = Point2f(rng.range(-450.0f, 450.0f), rng.range(-450.0f, 450.0f));
        float angle = rng.range(0.0f, 2.0f * Pi), dist = 12.0f * std::sqrt(rng.uniform());
        float x = cluster.x() + dist * std::cos(angle), z = cluster.y() + dist * std::sin(angle);
        float r = rng.range(0.2f, 0.5f), ry = rng.range(0.15f, 0.4f);
        Point3f c(x, height(x, z), z);
        b.cubeSphere(rockN, [&](const Vector3f &d) {
            float bump = 1.0f + 0.25f * rockShape(d + c);
            return Point3f(c + Vector3f(r * bump * d.x(), ry * d.y(), r * bump * d.z()));
        });
    }
    GeneratedScene s;
    s.shape = "wide";
    s.description = "1000 x 1 x 1000 rolling plain with clusters of small rocks";
    s.mesh = b.take();
    s.camera.origin = Point3f(-8.0f, 7.0f, 445.0f);
    s.camera.target = Point3f(0.0f, 0.0f, 420.0f);
    s.camera.fov = 60.0f;
    s.camera.nearClip = 0.01f;
    s.aoLength = 2.0f;
    s.integrator = "normals";  // ambient occlusion is nearly uniform here
    return s;
}

} // namespace nori::gen
