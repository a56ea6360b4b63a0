/// \file hair.cpp
/// \brief "hair": a head (sphere of radius 1) with thousands of long strands, each a ribbon of
/// short segments that leaves the scalp along its normal and falls under gravity over the
/// head. Millions of nearly parallel slivers a few millimetres wide, packed so densely that
/// rays pass close to hundreds of them; the strands' chains bend through many cells.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include <cmath>

namespace nori::gen {

namespace {
const int Segments = 12;      // ribbon segments per strand: 2 * Segments triangles
const float Skin = 1.015f;    // strands stay this far out from the head's centre
}

GeneratedScene generateHair(const GenParams &params) {
    MeshBuilder b;
    int n = std::max(2, int(std::lround(std::sqrt(double(params.triangles) / 20.0 / 12.0))));
    b.sphere(Point3f(0, 0, 0), 1.0f, n);
    GenRandom rng(params.seed, 18);
    uint64_t left = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
    uint64_t strands = std::max<uint64_t>(1, left / uint64_t(2 * Segments));
    for (uint64_t k = 0; k < strands; ++k) {
        // Roots on the scalp: the upper part of the head and the back, not the face (+z).
        Vector3f root;
        do root = rng.direction();
        while (root.y() < -0.25f || (root.z() > 0.45f && root.y() < 0.55f));
        float length = rng.range(0.8f, 1.6f), step = length / float(Segments);
        float width = rng.range(0.004f, 0.008f);
        Point3f p = Point3f(root * Skin);
        Vector3f dir = root;
        // The ribbon's side: any direction across the strand, re-orthogonalised as it bends.
        Vector3f side = root.cross(rng.direction()).normalized();
        Point3f prevL = p - 0.5f * width * side, prevR = p + 0.5f * width * side;
        for (int s = 1; s <= Segments; ++s) {
            // Gravity pulls the strand down; a little curl keeps neighbours from lying parallel.
            dir = (dir + Vector3f(0.0f, -0.35f, 0.0f) + 0.15f * rng.direction()).normalized();
            p += step * dir;
            if (p.norm() < Skin) p = Point3f(p.normalized() * Skin);  // rest on the head, not in it
            side = (side - side.dot(dir) * dir).normalized();
            float w = width * (1.0f - 0.8f * float(s) / float(Segments));
            Point3f l = p - 0.5f * w * side, r = p + 0.5f * w * side;
            b.quad(prevL, prevR, r, l);
            prevL = l;
            prevR = r;
        }
    }
    GeneratedScene s;
    s.shape = "hair";
    s.description = "head of radius 1 with long strands (ribbons of slivers) falling over it";
    s.mesh = b.take();
    s.camera.origin = Point3f(3.0f, 0.6f, 4.3f);
    s.camera.target = Point3f(0.0f, -0.55f, 0.0f);
    s.camera.fov = 45.0f;
    s.aoLength = 0.2f;
    return s;
}

} // namespace nori::gen
