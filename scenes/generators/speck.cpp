/// \file speck.cpp
/// \brief "speck": a rock about 1 across resting at the centre of a ground quad 100,000 across,
/// right on the diagonal that splits the quad into its two triangles. A ground that reaches
/// the horizon, as users model one, under a small object: every ray that meets the ground near
/// the rock meets it within float rounding of that diagonal (the ground's corners lie 50,000
/// away), so the watertight kernel cannot decide it in float and takes its exact path, and the
/// hit distance on a triangle that large needs the plane equation in double.
#include "shape_generators.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <cmath>

namespace nori::gen {

GeneratedScene generateSpeck(const GenParams &params) {
    const float half = 50000.0f;
    MeshBuilder b;
    // (a, b, c) and (a, c, d): the diagonal from (-half, -half) to (half, half) runs through the
    // origin, under the rock; the normal is +y.
    b.quad(Point3f(-half, 0, -half), Point3f(-half, 0, half), Point3f(half, 0, half), Point3f(half, 0, -half));
    const uint64_t rock = params.triangles > 2 ? params.triangles - 2 : 12;
    const int n = std::max(1, int(std::lround(std::sqrt(double(rock) / 12.0))));
    WaveNoise noise(params.seed, 4, 48, 1.5f, 40.0f, 1.0f);
    // Radius about 0.5, sunk a little into the ground as a rock lies.
    b.cubeSphere(n, [&](const Vector3f &d) {
        const float r = 0.5f + 0.15f * noise(d) - 0.05f * std::abs(noise(2.0f * d));
        return Point3f(r * d.x(), 0.35f + r * d.y(), r * d.z());
    });
    GeneratedScene s;
    s.shape = "speck";
    s.description = "rock 1 across on the diagonal of a ground quad 100,000 across";
    s.mesh = b.take();
    // Looking down at the rock, the horizon out of view: near it, rays graze a ground whose
    // corners' rounding (about 0.004 at 50,000) tilts its plane by 1e-7, and their hit
    // distances would say more about that than about the octree.
    s.camera.origin = Point3f(1.7f, 1.4f, 2.3f);
    s.camera.target = Point3f(0.0f, 0.15f, 0.0f);
    s.camera.fov = 40.0f;
    s.camera.nearClip = 1e-3f;
    s.camera.farClip = 1e6f;
    s.aoLength = 0.3f;
    s.integrator = "normals";  // under ambient occlusion the rock is white on a white ground
    return s;
}

} // namespace nori::gen
