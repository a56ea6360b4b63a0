/// \file stadium.cpp
/// \brief "stadium": the "teapot in a stadium": a finely tessellated rock 0.2 across at the
/// centre of a terraced bowl 300 across, camera next to the rock. Two clusters of very
/// different triangle sizes, with empty space between them.
#include "shape_generators.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <cmath>

namespace nori::gen {

GeneratedScene generateStadium(const GenParams &params) {
    // Half the budget for the stands, half for the small object.
    const int segments = 512;
    const float inner = 60.0f, outer = 150.0f, rise = 40.0f;
    int steps = std::max(1, int(params.triangles / 2 / (uint64_t(segments) * 4)));
    MeshBuilder b;
    // Field: one quad inside the stands.
    b.quad(Point3f(-inner, 0, -inner), Point3f(-inner, 0, inner), Point3f(inner, 0, inner), Point3f(inner, 0, -inner));
    // Terraces: each step is a vertical riser followed by a horizontal tread.
    b.grid(segments, 2 * steps, [&](int i, int j) {
        float phi = 2.0f * Pi * float(i % segments) / float(segments);
        // j even -> odd: riser (same radius, one step up); odd -> even: tread (one step out).
        float r = inner * 1.42f + (outer - inner * 1.42f) * float(j / 2) / float(steps);
        float y = rise * float((j + 1) / 2) / float(steps);
        return Point3f(r * std::cos(phi), y, r * std::sin(phi));
    });
    // The "teapot": a displaced sphere of radius 0.1 on a slim pedestal.
    uint64_t left = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
    int n = std::max(1, int(std::lround(std::sqrt(double(left) / 12.0))));
    WaveNoise noise(params.seed, 10, 32, 2.0f, 30.0f, 1.0f);
    Point3f center(0.0f, 0.35f, 0.0f);
    b.cubeSphere(n, [&](const Vector3f &d) { return Point3f(center + 0.1f * (1.0f + 0.25f * noise(d)) * d); });
    b.box(Point3f(-0.02f, 0.0f, -0.02f), Point3f(0.02f, 0.28f, 0.02f));
    GeneratedScene s;
    s.shape = "stadium";
    s.description = "displaced sphere 0.2 across at the centre of a terraced stadium 300 across";
    s.mesh = b.take();
    s.camera.origin = Point3f(0.42f, 0.5f, 0.55f);
    s.camera.target = center;
    s.camera.fov = 60.0f;
    s.camera.nearClip = 1e-3f;
    s.aoLength = 0.1f;
    s.integrator = "normals";  // ambient occlusion is nearly uniform here
    return s;
}

} // namespace nori::gen
