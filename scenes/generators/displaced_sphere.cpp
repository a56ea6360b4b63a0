/// \file displaced_sphere.cpp
/// \brief "sphere": a sphere whose radius is displaced by smooth noise of many octaves
/// (a rock or asteroid): a compact closed mesh like a scan, but with steep ridges that
/// stretch triangles into slivers.
#include "shape_generators.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <cmath>

namespace nori::gen {

GeneratedScene generateDisplacedSphere(const GenParams &params) {
    int n = std::max(1, int(std::lround(std::sqrt(double(params.triangles) / 12.0))));
    WaveNoise noise(params.seed, 4, 48, 1.5f, 40.0f, 1.0f);
    MeshBuilder b;
    b.cubeSphere(n, [&](const Vector3f &d) {
        // |noise| folds the valleys into sharp creases.
        float r = 1.0f + 0.35f * noise(d) - 0.12f * std::abs(noise(2.0f * d));
        return Point3f(r * d);
    });
    GeneratedScene s;
    s.shape = "sphere";
    s.description = "noise-displaced sphere (rock), radius about 1";
    s.mesh = b.take();
    s.camera.origin = Point3f(2.2f, 1.5f, 3.0f);
    s.camera.target = Point3f(0, 0, 0);
    s.camera.fov = 40.0f;
    s.aoLength = 0.5f;
    s.integrator = "normals";  // ambient occlusion is nearly uniform here
    return s;
}

} // namespace nori::gen
