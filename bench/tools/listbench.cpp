/// \file listbench.cpp
/// \brief nori-listbench: what one triangle list test costs with its data in cache (Google
/// Benchmark). A list is what the octree tests at a leaf or a node's kept group
/// (TriangleStore::intersect); nori-sahref shows the octree tests about as many of them per ray
/// as a SAH BVH tests blocks of four triangles, so their price is where the two differ.
///
/// Cases: lists of 2 to 128 triangles (random small triangles in a cube; lists above 16 carry
/// block boxes), rays that miss every triangle ("miss") or aim at one triangle's centroid
/// ("hit"), and the per-ray setup of the watertight kernel (TriangleRay). Run with
/// --benchmark_repetitions=N for spread; no assertion is made on any time.
#include "accel/triangle.h"
#include <benchmark/benchmark.h>
#include <memory>
#include <random>
#include <vector>

using namespace nori;

namespace {

/// One leaf of \p n triangles and \p count rays, built once per case.
struct ListCase {
    uint32_t n;
    TriangleStore store;
    std::vector<Ray3f> rays;
    std::vector<TriangleRay> triangleRays;

    ListCase(uint32_t triangles, bool aimed, int count = 4096) : n(triangles) {
        std::mt19937 rng(20261201u);
        std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
        std::vector<std::array<Point3f, 3>> corners(n);
        for (auto &t : corners) {
            const Point3f centre(5.0f * uniform(rng), 5.0f * uniform(rng), 5.0f * uniform(rng));
            for (Point3f &p : t) p = centre + 0.5f * Point3f(uniform(rng), uniform(rng), uniform(rng));
        }
        std::vector<uint32_t> ids(n);
        for (uint32_t i = 0; i < n; ++i) ids[i] = i;
        store.reset(Intersector::Watertight, TriangleStore::leafWords(n));
        store.setLeaf(0, ids.data(), n, corners);
        for (int k = 0; k < count; ++k) {
            const Point3f origin(20.0f * uniform(rng), 20.0f * uniform(rng), 30.0f);
            const auto &t = corners[size_t(k) % n];
            // Aimed: through a triangle's centroid. Otherwise far beside the cube.
            const Point3f target = aimed ? Point3f((t[0] + t[1] + t[2]) / 3.0f) : Point3f(50.0f + uniform(rng), 50.0f, 0.0f);
            rays.emplace_back(origin, Vector3f(target - origin));
            triangleRays.emplace_back(rays.back());
        }
    }
};

void listTest(benchmark::State &state) {
    const uint32_t n = uint32_t(state.range(0));
    const ListCase c(n, state.range(1) != 0);
    size_t k = 0, hits = 0;
    for (auto _ : state) {
        Hit hit;
        hit.t = c.rays[k].maxt;
        hits += c.store.intersect(c.triangleRays[k], 0, n, hit);
        benchmark::DoNotOptimize(hit);
        k = (k + 1) & 4095u;
    }
    state.counters["hits_per_list"] = benchmark::Counter(double(hits), benchmark::Counter::kAvgIterations);
}
BENCHMARK(listTest)->ArgNames({"triangles", "aimed"})->ArgsProduct({{2, 8, 16, 64, 128}, {0, 1}});

/// Lists taken in a random order: what the branches inside a list test cost when they cannot
/// be learnt from the previous call (as in a traversal, where each list differs from the last),
/// against the same cases taken one at a time above. Arguments: sizes (0: 2 to 128 mixed, else
/// that size only) and aimed (0: misses, 1: hits, 2: both mixed).
void mixedLists(benchmark::State &state) {
    const uint32_t only = uint32_t(state.range(0));
    const int aimedMode = int(state.range(1));
    std::vector<std::unique_ptr<ListCase>> cases;
    for (uint32_t n : {2u, 8u, 16u, 64u, 128u}) {
        if (only && n != only) continue;
        for (bool aimed : {false, true}) {
            if ((aimedMode == 0 && aimed) || (aimedMode == 1 && !aimed)) continue;
            cases.push_back(std::make_unique<ListCase>(n, aimed, 256));
        }
    }
    std::mt19937 rng(7);
    std::vector<uint8_t> order(8192);
    for (uint8_t &o : order) o = uint8_t(rng() % cases.size());
    size_t k = 0;
    for (auto _ : state) {
        const ListCase &c = *cases[order[k & 8191u]];
        const size_t r = (k >> 3) & 255u;
        Hit hit;
        hit.t = c.rays[r].maxt;
        benchmark::DoNotOptimize(c.store.intersect(c.triangleRays[r], 0, c.n, hit));
        benchmark::DoNotOptimize(hit);
        ++k;
    }
}
BENCHMARK(mixedLists)->ArgNames({"size", "aimed"})->ArgsProduct({{0, 8, 64}, {0, 1, 2}});

void triangleRaySetup(benchmark::State &state) {
    const ListCase c(2, false);
    size_t k = 0;
    for (auto _ : state) {
        TriangleRay ray(c.rays[k]);
        benchmark::DoNotOptimize(ray);
        k = (k + 1) & 4095u;
    }
}
BENCHMARK(triangleRaySetup);

} // namespace

BENCHMARK_MAIN();
