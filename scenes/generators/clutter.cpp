/// \file clutter.cpp
/// \brief "clutter": stones at wildly mixed scales on a mountainside: pebbles of 2 cm next to
/// the camera, rocks, boulders of 40 m further out, a mountain 500 high in the distance, every
/// stone with the same tessellation (as one scanned rock placed at many scales). Triangle
/// edges span four orders of magnitude, and the small ones crowd a speck of the bounds.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <cmath>

namespace nori::gen {

namespace {
const float Half = 1000.0f;
const int StoneN = 3;     // 108 triangles per stone
const float Eye = 1.5f;  // the camera stands at (0, z = Eye), looking towards -z

/// The terrain: a mountain behind the origin (looking towards -z), rolling ground around it,
/// flat where the pebbles lie.
struct Terrain {
    WaveNoise noise;
    int cells;

    float height(float x, float z) const {
        float dx = x, dz = z + 700.0f;
        float mountain = 500.0f * std::exp(-(dx * dx + dz * dz) / (2.0f * 260.0f * 260.0f));
        float calm = std::min(1.0f, std::sqrt(x * x + z * z) / 200.0f);  // quiet near the origin
        return mountain + 12.0f * calm * noise(x, z);
    }
    float coordinate(int i) const { return -Half + 2.0f * Half * float(i) / float(cells); }
    /// Height of the triangulated grid itself (MeshBuilder::grid's diagonals), so that stones
    /// sit on the surface that is rendered, not on the smooth function.
    float surface(float x, float z) const {
        float step = 2.0f * Half / float(cells);
        int i = std::clamp(int((x + Half) / step), 0, cells - 1), j = std::clamp(int((z + Half) / step), 0, cells - 1);
        float u = (x - coordinate(i)) / step, v = (z - coordinate(j)) / step;
        float h00 = height(coordinate(i), coordinate(j)), h10 = height(coordinate(i + 1), coordinate(j));
        float h01 = height(coordinate(i), coordinate(j + 1)), h11 = height(coordinate(i + 1), coordinate(j + 1));
        if ((i + j) & 1)  // diagonal (i, j) - (i + 1, j + 1)
            return u > v ? h00 + u * (h10 - h00) + v * (h11 - h10) : h00 + v * (h01 - h00) + u * (h11 - h01);
        // diagonal (i + 1, j) - (i, j + 1)
        return u + v < 1.0f ? h00 + u * (h10 - h00) + v * (h01 - h00)
                            : h11 + (1.0f - u) * (h01 - h11) + (1.0f - v) * (h10 - h11);
    }
};
} // namespace

GeneratedScene generateClutter(const GenParams &params) {
    Terrain terrain{WaveNoise(params.seed, 15, 16, 2.0f * Pi / 600.0f, 2.0f * Pi / 20.0f, 1.0f),
                    std::max(1, int(std::sqrt(double(params.triangles) / 20.0)))};
    MeshBuilder b;
    b.grid(terrain.cells, terrain.cells, [&](int i, int j) {
        float x = terrain.coordinate(i), z = terrain.coordinate(j);
        return Point3f(x, terrain.height(x, z), z);
    });
    GenRandom rng(params.seed, 16);
    WaveNoise shape(params.seed, 17, 12, 1.5f, 8.0f, 1.0f);
    const uint64_t perStone = uint64_t(12 * StoneN * StoneN);
    uint64_t stones = std::max<uint64_t>(1, (params.triangles - std::min(params.triangles, b.triangleCount())) / perStone);
    for (uint64_t k = 0; k < stones; ++k) {
        // As many stones in every decade of size; each lies within 30 of its sizes of the
        // origin, so pebbles gather at the camera's feet and boulders spread over the land.
        float size = rng.logRange(0.02f, 40.0f);
        // A stone may not swallow the camera or bury the pebbles in front of it: draw again.
        float x, z;
        do {
            float angle = rng.range(0.0f, 2.0f * Pi), dist = 30.0f * size * std::sqrt(rng.uniform());
            x = dist * std::cos(angle), z = dist * std::sin(angle) - 2.0f;
        } while (std::hypot(x, z - Eye) < 1.4f * size + 0.3f ||
                 (size > 0.3f && std::hypot(x, z + 2.0f) < 1.4f * size + 1.0f));
        Vector3f seedOffset = 10.0f * rng.direction();
        float squash = rng.range(0.45f, 0.8f);
        // Sunk by a third of its height, as stones lie.
        Point3f c(x, terrain.surface(x, z) + 0.3f * squash * size, z);
        b.cubeSphere(StoneN, [&](const Vector3f &d) {
            float r = size * (1.0f + 0.3f * shape(d + seedOffset));
            return Point3f(c + Vector3f(r * d.x(), squash * r * d.y(), r * d.z()));
        });
    }
    GeneratedScene s;
    s.shape = "clutter";
    s.description = "stones from 2 cm to 40 m on a mountainside, camera among the pebbles";
    s.mesh = b.take();
    s.camera.origin = Point3f(0.0f, terrain.surface(0.0f, Eye) + 1.0f, Eye);
    s.camera.target = Point3f(0.0f, terrain.surface(0.0f, -3.0f) + 0.5f, -3.0f);
    s.camera.fov = 60.0f;
    s.camera.nearClip = 1e-3f;
    s.aoLength = 0.5f;
    return s;
}

} // namespace nori::gen
