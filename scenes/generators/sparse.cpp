/// \file sparse.cpp
/// \brief "sparse": an asteroid field: small detailed rocks (1-6 across) scattered far apart
/// through a cube 2000 across, cut diagonally by a planetary ring of eight huge triangles.
/// Almost all of the bounds is empty, the detail sits in isolated specks, and the only large
/// triangles are tilted, so they cross cells on every axis (the other shapes' large triangles
/// are axis-aligned floors and walls).
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <cmath>

namespace nori::gen {

namespace {
const float Half = 1000.0f;
const uint64_t TrianglesPerRock = 600;  // sets how many rocks a budget buys
}

GeneratedScene generateSparse(const GenParams &params) {
    MeshBuilder b;
    // The ring: an annulus of 8 sectors (one triangle each) tilted about x and z, through the
    // centre of the cube, its outer corners on the cube's faces.
    const int sectors = 8;
    Vector3f axisA = Vector3f(1.0f, 0.35f, 0.0f).normalized(), axisB = Vector3f(0.0f, 0.5f, 1.0f).normalized();
    axisB = (axisB - axisB.dot(axisA) * axisA).normalized();
    for (int k = 0; k < sectors; ++k) {
        auto rim = [&](int i, float r) {
            float phi = 2.0f * Pi * float(i % sectors) / float(sectors);
            return Point3f(r * (std::cos(phi) * axisA + std::sin(phi) * axisB));
        };
        // Each sector is one triangle from the inner rim to two outer corners.
        b.triangle(rim(k, 250.0f), rim(k, 950.0f), rim(k + 1, 950.0f));
    }
    GenRandom rng(params.seed, 19);
    WaveNoise shape(params.seed, 20, 16, 1.5f, 12.0f, 1.0f);
    uint64_t left = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
    uint64_t rocks = std::max<uint64_t>(1, left / TrianglesPerRock);
    int n = std::max(1, int(std::lround(std::sqrt(double(left / rocks) / 12.0))));
    // The camera floats above the ring, looking along it.
    const Point3f eye = Point3f(0, 0, 0) + 420.0f * axisA + 60.0f * axisA.cross(axisB);
    const Vector3f view = (axisB - 0.3f * axisA).normalized();
    const Point3f swarm = eye + 160.0f * view;
    for (uint64_t k = 0; k < rocks; ++k) {
        // A tenth of the rocks drift in a swarm ahead of the camera, still tens apart; the
        // rest are spread through the whole cube.
        Point3f c = k < rocks / 10 ? swarm + 120.0f * std::cbrt(rng.uniform()) * rng.direction()
                                   : Point3f(rng.range(-Half, Half), rng.range(-Half, Half), rng.range(-Half, Half));
        if (k == 0) c = eye + 25.0f * view;
        float size = rng.logRange(0.5f, 3.0f);
        Vector3f offset = 10.0f * rng.direction();
        b.cubeSphere(n, [&](const Vector3f &d) { return Point3f(c + size * (1.0f + 0.35f * shape(d + offset)) * d); });
    }
    GeneratedScene s;
    s.shape = "sparse";
    s.description = "asteroid field: rocks far apart in a cube 2000 across, cut by a tilted ring";
    s.mesh = b.take();
    s.camera.origin = eye;
    s.camera.target = eye + view - 0.25f * axisA.cross(axisB);
    s.camera.fov = 55.0f;
    s.camera.nearClip = 0.01f;
    s.aoLength = 5.0f;
    s.integrator = "normals";  // ambient occlusion is nearly uniform here
    return s;
}

} // namespace nori::gen
