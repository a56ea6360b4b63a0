/// \file heightfield.cpp
/// \brief "heightfield": a terrain strip 1000 long (x), 1 tall (y) and 8 wide (z), seen
/// from just above one end: bounds 1000x longer than tall and rays that graze the surface
/// over hundreds of cells.
#include "shape_generators.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <algorithm>
#include <cmath>
#include <vector>

namespace nori::gen {

GeneratedScene generateHeightfield(const GenParams &params) {
    const float length = 1000.0f, width = 8.0f;
    const int nz = 16;
    int nx = std::max(1, int(params.triangles / (2 * nz)));
    // Rolling hills (periods of tens of units) with finer detail.
    WaveNoise noise(params.seed, 3, 24, 2.0f * Pi / 120.0f, 2.0f * Pi / 3.0f, 0.8f);
    auto x = [&](int i) { return -0.5f * length + length * float(i) / float(nx); };
    auto z = [&](int j) { return -0.5f * width + width * float(j) / float(nz); };
    // Rescale the heights to exactly [0, 1], so the strip is 1000x longer than tall.
    std::vector<float> h(size_t(nx + 1) * size_t(nz + 1));
    for (int j = 0; j <= nz; ++j)
        for (int i = 0; i <= nx; ++i) h[size_t(j) * size_t(nx + 1) + size_t(i)] = noise(x(i), z(j));
    auto [lo, hi] = std::minmax_element(h.begin(), h.end());
    float low = *lo, scale = *hi > *lo ? 1.0f / (*hi - *lo) : 0.0f;
    MeshBuilder b;
    b.grid(nx, nz, [&](int i, int j) {
        return Point3f(x(i), (h[size_t(j) * size_t(nx + 1) + size_t(i)] - low) * scale, z(j));
    });
    GeneratedScene s;
    s.shape = "heightfield";
    s.description = "terrain strip 1000 x 1 x 8 seen at a grazing angle from one end";
    s.mesh = b.take();
    s.camera.origin = Point3f(-0.5f * length - 6.0f, 2.2f, 0.0f);
    s.camera.target = Point3f(-0.5f * length + 60.0f, 0.4f, 0.0f);
    s.camera.fov = 45.0f;
    s.camera.width = 640;
    s.camera.height = 360;
    s.aoLength = 3.0f;
    s.integrator = "normals";  // ambient occlusion is nearly uniform here
    return s;
}

} // namespace nori::gen
