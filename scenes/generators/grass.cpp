/// \file grass.cpp
/// \brief "grass": thin tapered blades (two long thin triangles each, ~30:1) standing on a
/// ground quad, seen from eye height: foliage-like geometry whose triangles have long,
/// slanted bounding boxes and crowd every cell they touch.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <cmath>

namespace nori::gen {

GeneratedScene generateGrass(const GenParams &params) {
    const float half = 5.0f;
    uint64_t blades = std::max<uint64_t>(1, (params.triangles - 2) / 2);
    GenRandom rng(params.seed, 2);
    MeshBuilder b;
    b.quad(Point3f(-half, 0, -half), Point3f(-half, 0, half), Point3f(half, 0, half), Point3f(half, 0, -half));
    for (uint64_t k = 0; k < blades; ++k) {
        Point3f base(rng.range(-half, half), 0.0f, rng.range(-half, half));
        float facing = rng.range(0.0f, Pi);
        Vector3f side(std::cos(facing), 0.0f, std::sin(facing));
        float width = rng.range(0.006f, 0.014f), height = rng.range(0.15f, 0.45f);
        // The tip leans away from the vertical by up to ~35 degrees, in any direction.
        float leanAngle = rng.range(0.0f, 2.0f * Pi), lean = height * rng.range(0.0f, 0.7f);
        Vector3f tipOffset(lean * std::cos(leanAngle), height, lean * std::sin(leanAngle));
        Point3f tip = base + tipOffset;
        float tipWidth = 0.25f * width;
        b.quad(base - 0.5f * width * side, base + 0.5f * width * side, tip + 0.5f * tipWidth * side,
               tip - 0.5f * tipWidth * side);
    }
    GeneratedScene s;
    s.shape = "grass";
    s.description = "thin grass blades (2 long thin triangles each) on a 10 x 10 ground quad";
    s.mesh = b.take();
    s.camera.origin = Point3f(0.8f, 1.1f, 6.2f);
    s.camera.target = Point3f(0, 0.05f, 0.5f);
    s.camera.fov = 50.0f;
    s.aoLength = 0.3f;
    return s;
}

} // namespace nori::gen
