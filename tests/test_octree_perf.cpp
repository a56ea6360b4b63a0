// Octree timing against Embree: a measurement tool, not a test (nothing is asserted, and it is
// disabled by default). Run it with
//   build/tests/nori-tests --gtest_also_run_disabled_tests --gtest_filter='*OctreePerf*'
// Environment: NORI_PERF_MESH (default: the full dragon), NORI_PERF_CONFIGS (';'-separated
// "traversal,intersector,maxDepth,leafSize,overlap"), NORI_PERF_REPEATS (default 3).
#include <gtest/gtest.h>
#include <nori/objloader.h>
#include <nori/octree.h>
#include <embree_oracle.h>
#include <ray_sets.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <sstream>

using namespace nori;

namespace {

std::string env(const char *name, const std::string &fallback) {
    const char *value = std::getenv(name);
    return value && *value ? value : fallback;
}

/// Median wall time (ms) of \p repeats runs of \p fn.
template <typename Fn> double medianMs(int repeats, Fn &&fn) {
    std::vector<double> ms;
    for (int r = 0; r < repeats; ++r) {
        auto start = std::chrono::steady_clock::now();
        fn();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

volatile size_t g_sink;

} // namespace

TEST(OctreePerf, DISABLED_TimeAgainstEmbree) {
    std::string path = env("NORI_PERF_MESH", std::string(NORI_SHARED_DIR) + "/meshes/dragon_vrip.obj.gz");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
    int repeats = std::stoi(env("NORI_PERF_REPEATS", "3"));
    Mesh mesh(loadObjFile(path), path);
    std::vector<const Mesh *> meshes{&mesh};
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);

    EmbreeOracle robust(meshes);
    EmbreeOracle fast(meshes, EmbreeOracle::Options{false, 1});
    MeshTable table(meshes);
    auto camera = framingCamera(mesh.bbox(), 1024, 768);
    auto hitFn = [&](const Ray3f &r, Hit &h) { return robust.intersect(r, h); };
    std::vector<Ray3f> primary = cameraRays(*camera, 1, 1);
    std::vector<Ray3f> diffuse = diffuseRays(primary, hitFn, table, 2);
    std::vector<Ray3f> shadow = surfaceShadowRays(primary, hitFn, table, primary.size(), 3);
    std::vector<Ray3f> random = randomBoxRays(mesh.bbox(), primary.size(), 4);
    struct Set { const char *name; const std::vector<Ray3f> *rays; bool anyHit; };
    const Set sets[] = {{"primary", &primary, false}, {"diffuse", &diffuse, false}, {"shadow", &shadow, true},
                        {"random", &random, false}};

    auto timeSet = [&](const Set &s, auto &&closest, auto &&any, int times) {
        return medianMs(times, [&] {
            size_t hits = 0;
            Hit h;
            for (const Ray3f &r : *s.rays) hits += s.anyHit ? any(r) : closest(r, h);
            g_sink = hits;
        });
    };
    double embreeMs[4];
    for (int i = 0; i < 4; ++i)
        embreeMs[i] = timeSet(sets[i], [&](const Ray3f &r, Hit &h) { return fast.intersect(r, h); },
                              [&](const Ray3f &r) { return fast.occluded(r); }, repeats);
    std::printf("mesh %s: %u triangles; rays: primary %zu, diffuse %zu, shadow %zu, random %zu\n", path.c_str(),
                mesh.triangleCount(), primary.size(), diffuse.size(), shadow.size(), random.size());
    std::printf("embree (non-robust, 1 thread): build %.1f ms, %.1f MB, Mrays/s primary %.2f diffuse %.2f shadow "
                "%.2f random %.2f\n",
                fast.buildMilliseconds(), fast.bytes() / 1e6, primary.size() / embreeMs[0] / 1e3,
                diffuse.size() / embreeMs[1] / 1e3, shadow.size() / embreeMs[2] / 1e3, random.size() / embreeMs[3] / 1e3);
    std::printf("%-8s %-10s %3s %3s %-5s | %8s %8s %7s %7s | %6s %6s %6s %6s | %5s %5s %5s %5s | %s\n", "trav",
                "isect", "dep", "lf", "ovl", "build", "MB", "inner", "refs/t", "prim", "diff", "shad", "rand", "xP", "xD",
                "xS", "xR", "mismatch(p/d/r)");

    std::stringstream configs(env("NORI_PERF_CONFIGS", "simd,watertight,16,8,exact;simd,mt,16,8,exact"));
    std::string config;
    while (std::getline(configs, config, ';')) {
        std::stringstream fields(config);
        std::string trav, isect, depth, leaf, overlap;
        std::getline(fields, trav, ',');
        std::getline(fields, isect, ',');
        std::getline(fields, depth, ',');
        std::getline(fields, leaf, ',');
        std::getline(fields, overlap, ',');
        PropertyList props;
        props.setString("traversal", trav);
        props.setString("intersector", isect);
        props.setInteger("maxDepth", std::stoi(depth));
        props.setInteger("leafSize", std::stoi(leaf));
        props.setString("overlap", overlap);
        OctreeAccel octree(props);
        octree.addMesh(&mesh);
        octree.build();
        double stat[16] = {};
        auto stats = octree.statistics();
        for (size_t i = 0; i < stats.size() && i < 16; ++i) stat[i] = stats[i].value;
        double ms[4];
        size_t mismatch[4] = {};
        for (int i = 0; i < 4; ++i) {
            // Interleaved: Embree, octree, Embree, octree, ...; medians of each.
            std::vector<double> eMs, oMs;
            for (int r = 0; r < repeats; ++r) {
                eMs.push_back(timeSet(sets[i], [&](const Ray3f &ray, Hit &h) { return fast.intersect(ray, h); },
                                      [&](const Ray3f &ray) { return fast.occluded(ray); }, 1));
                oMs.push_back(timeSet(sets[i], [&](const Ray3f &ray, Hit &h) { return octree.intersect(ray, h); },
                                      [&](const Ray3f &ray) { return octree.occluded(ray); }, 1));
            }
            std::sort(eMs.begin(), eMs.end());
            std::sort(oMs.begin(), oMs.end());
            embreeMs[i] = eMs[eMs.size() / 2];
            ms[i] = oMs[oMs.size() / 2];
            for (const Ray3f &r : *sets[i].rays) {
                if (sets[i].anyHit) continue;
                Hit a, b;
                bool ha = octree.intersect(r, a), hb = robust.intersect(r, b);
                if (ha != hb || (ha && a.prim != b.prim && std::abs(a.t - b.t) > 1e-5f * b.t)) ++mismatch[i];
            }
        }
        // stats: build_ms, triangles, internal, leaves, empty, avg, depth, refs, bytes
        std::printf("%-8s %-10s %3s %3s %-5s | %8.1f %8.1f %7.0f %7.2f | %6.2f %6.2f %6.2f %6.2f | %5.2f %5.2f %5.2f "
                    "%5.2f | %zu/%zu/%zu\n",
                    trav.c_str(), isect.c_str(), depth.c_str(), leaf.c_str(), overlap.c_str(), stat[0],
                    stat[8] / 1e6, stat[2], stat[7] / stat[1], primary.size() / ms[0] / 1e3,
                    diffuse.size() / ms[1] / 1e3, shadow.size() / ms[2] / 1e3, random.size() / ms[3] / 1e3,
                    embreeMs[0] / ms[0], embreeMs[1] / ms[1], embreeMs[2] / ms[2], embreeMs[3] / ms[3], mismatch[0],
                    mismatch[1], mismatch[3]);
        std::fflush(stdout);
    }
}
