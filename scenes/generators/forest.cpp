/// \file forest.cpp
/// \brief "forest": trees of mixed sizes on rolling terrain, seen from eye height at the
/// forest's edge: tapered trunks and branches (long slanted tubes) and dense crowns of small,
/// randomly oriented leaf quads. Unlike grass, the fine geometry fills volumes (clouds of
/// leaves in mid-air) instead of standing on one plane, and crowns overlap one another.
#include "shape_generators.h"
#include "gen_random.h"
#include "mesh_builder.h"
#include "wave_noise.h"
#include <cmath>

namespace nori::gen {

namespace {
const float Half = 30.0f;                 // the forest covers [-Half, Half]^2
const uint64_t TrianglesPerTree = 2500;  // sets how many trees a budget buys
const int TrunkSegments = 8, TrunkRings = 5, Branches = 6, BranchSegments = 5;

/// One tree of height about 12 \p scale at \p base: trunk, Branches branches, and
/// \p leaves leaves spread over clusters at the branch tips and around the top.
void tree(MeshBuilder &b, GenRandom &rng, const Point3f &base, float scale, uint64_t leaves) {
    float height = 12.0f * scale, radius = 0.25f * scale;
    for (int k = 0; k < TrunkRings; ++k) {
        // Rings along one axis weld, so the trunk is one tube.
        float t0 = float(k) / float(TrunkRings), t1 = float(k + 1) / float(TrunkRings);
        b.tube(base + Vector3f(0, height * t0, 0), base + Vector3f(0, height * t1, 0), radius * (1.0f - 0.7f * t0),
               radius * (1.0f - 0.7f * t1), TrunkSegments);
    }
    std::vector<Point3f> clusters{base + Vector3f(0, height, 0)};
    for (int k = 0; k < Branches; ++k) {
        float t = rng.range(0.35f, 0.85f), angle = rng.range(0.0f, 2.0f * Pi);
        float length = height * rng.range(0.2f, 0.4f) * (1.1f - 0.5f * t);
        Point3f from = base + Vector3f(0, height * t, 0);
        Vector3f dir = Vector3f(std::cos(angle), rng.range(0.3f, 0.9f), std::sin(angle)).normalized();
        Point3f to = from + length * dir;
        float r = radius * (1.0f - 0.7f * t) * 0.5f;
        b.tube(from, to, r, 0.3f * r, BranchSegments);
        clusters.push_back(to);
    }
    // Leaves: small diamond quads (two triangles), 8-25 cm, in a ball around each cluster.
    float crown = 1.0f + 1.5f * scale;
    for (uint64_t k = 0; k < leaves; ++k) {
        const Point3f &c = clusters[size_t(rng.below(uint32_t(clusters.size())))];
        Vector3f offset = rng.direction() * crown * std::cbrt(rng.uniform());
        Point3f center = c + Vector3f(offset.x(), 0.7f * offset.y(), offset.z());
        Vector3f along = rng.direction(), across = along.cross(rng.direction());
        if (across.squaredNorm() < 1e-4f) across = along.cross(Vector3f(0, 1, 0));
        across.normalize();
        float length = rng.range(0.04f, 0.12f), width = 0.5f * length;
        b.quad(center - length * along, center - width * across, center + length * along, center + width * across);
    }
}
} // namespace

GeneratedScene generateForest(const GenParams &params) {
    WaveNoise terrain(params.seed, 11, 12, 2.0f * Pi / 80.0f, 2.0f * Pi / 6.0f, 1.2f);
    auto height = [&](float x, float z) { return 2.5f * terrain(x, z); };
    // The ground takes a tenth of the budget, the trees the rest.
    int cells = std::max(1, int(std::sqrt(double(params.triangles) / 20.0)));
    MeshBuilder b;
    const float ground = Half + 20.0f;
    b.grid(cells, cells, [&](int i, int j) {
        float x = -ground + 2.0f * ground * float(i) / float(cells), z = -ground + 2.0f * ground * float(j) / float(cells);
        return Point3f(x, height(x, z), z);
    });
    GenRandom rng(params.seed, 12);
    uint64_t treeBudget = params.triangles > b.triangleCount() ? params.triangles - b.triangleCount() : 0;
    uint64_t trees = std::max<uint64_t>(1, treeBudget / TrianglesPerTree);
    const Point3f eye(3.0f, 0.0f, Half + 7.0f);  // outside every crown
    // Sizes first (saplings to old trees, log-uniform), then leaves in proportion to the crown.
    std::vector<float> scales(trees);
    double weight = 0.0;
    for (float &s : scales) {
        s = rng.logRange(0.3f, 1.6f);
        weight += double(s) * double(s);
    }
    uint64_t wood = uint64_t(2 * TrunkSegments * TrunkRings + Branches * 2 * BranchSegments);
    uint64_t leafBudget = treeBudget > trees * wood ? treeBudget - trees * wood : trees;
    for (uint64_t k = 0; k < trees; ++k) {
        float x = rng.range(-Half, Half), z = rng.range(-Half, Half);
        if (k == 0) x = 1.0f, z = Half - 6.0f;  // one tree close to the camera
        uint64_t leaves = uint64_t(double(leafBudget) / 2.0 * double(scales[k]) * double(scales[k]) / weight);
        tree(b, rng, Point3f(x, height(x, z) - 0.2f, z), scales[k], std::max<uint64_t>(1, leaves));
    }
    GeneratedScene s;
    s.shape = "forest";
    s.description = "trees of mixed sizes (trunks, branches, leaf clusters) on rolling terrain";
    s.mesh = b.take();
    s.camera.origin = Point3f(eye.x(), height(eye.x(), eye.z()) + 1.7f, eye.z());
    s.camera.target = Point3f(0.0f, height(0.0f, 0.0f) + 5.0f, 0.0f);
    s.camera.fov = 65.0f;
    s.camera.nearClip = 1e-3f;
    s.aoLength = 1.0f;
    return s;
}

} // namespace nori::gen
