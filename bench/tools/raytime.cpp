/// \file raytime.cpp
/// \brief nori-raytime: builds the default octree of a scene and traces one of the bench's ray
/// sets (primary, diffuse or shadow) repeatedly, for a profiler (perf, callgrind).
/// Environment: NORI_LEAFSIZE=N sets leafSize; NORI_AB=PROP times the octree with the boolean
/// property PROP on against off, side by side in one run (the rays in alternating slices, or
/// the builds in turn), and prints the ratio; NORI_AB=embree the same for the octree against
/// Embree's default mode; NORI_EMBREE=1 times Embree's default mode on the same rays (or its
/// build, for the set `build`) instead of the octree (a peer for a profiler).
#include "accel/octree.h"
#include "embree_accel.h"
#include "tool_main.h"
#include <ray_sets.h>
#include <scene_geometry.h>
#include <nori/scene.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace nori;

namespace {
/// This thread's CPU time in nanoseconds (the machine is shared: wall time is noisy).
double cpuNs() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e9 * double(ts.tv_sec) + double(ts.tv_nsec);
}
} // namespace

namespace {
int run(int argc, char **argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: nori-raytime SCENE.xml primary|diffuse|shadow|build [repeats] [spp]\n");
        return 2;
    }
    // One thread, as nori-bench --threads 1 (the build's tasks would run on other threads).
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const std::string set = argv[2];
    if (set != "primary" && set != "diffuse" && set != "shadow" && set != "build") {
        std::fprintf(stderr, "nori-raytime: unknown set '%s' (primary, diffuse, shadow or build)\n", argv[2]);
        return 2;
    }
    const int repeats = argc > 3 ? std::atoi(argv[3]) : 10;
    if (repeats < 1) {
        std::fprintf(stderr, "nori-raytime: repeats must be a positive integer, not '%s'\n", argv[3]);
        return 2;
    }
    const int spp = argc > 4 ? std::atoi(argv[4]) : 4;
    std::unique_ptr<Scene> scene = loadSceneGeometry(argv[1]);
    std::vector<const Mesh *> meshes;
    for (const auto &m : scene->meshes()) meshes.push_back(m.get());
    MeshTable table(meshes);
    // NORI_LEAFSIZE: the octree's leafSize (for experiments; default: the accelerator's).
    PropertyList props;
    if (const char *ls = std::getenv("NORI_LEAFSIZE")) props.setInteger("leafSize", std::atoi(ls));
    OctreeAccel octree{props};
    for (const Mesh *m : meshes) octree.addMesh(m);
    // Embree's default mode on one thread (NORI_EMBREE), its meshes added.
    auto makeEmbree = [&] {
        PropertyList ep;
        ep.setInteger("threads", 1);
        auto embree = std::make_unique<bench::EmbreeAccel>(ep);
        for (const Mesh *m : meshes) embree->addMesh(m);
        return embree;
    };
    auto t0 = cpuNs();
    octree.build();
    auto t1 = cpuNs();
    // NORI_AB: two contenders, A and B, timed in turn in one process (A B B A), so that the
    // machine's drift, which moves separate processes by up to a factor of 1.8 on a shared
    // machine, hits both alike.
    const char *abName = std::getenv("NORI_AB");
    const bool abEmbree = abName && std::string(abName) == "embree";
    auto makeContender = [&](bool first) -> std::unique_ptr<Accel> {
        if (abEmbree) {
            if (!first) return makeEmbree();
            auto o = std::make_unique<OctreeAccel>(props);
            for (const Mesh *m : meshes) o->addMesh(m);
            return o;
        }
        PropertyList p = props;
        p.setBoolean(abName, first);
        auto o = std::make_unique<OctreeAccel>(p);
        for (const Mesh *m : meshes) o->addMesh(m);
        return o;
    };
    const std::string nameA = abEmbree ? "octree" : std::string(abName ? abName : "") + "=true";
    const std::string nameB = abEmbree ? "embree" : std::string(abName ? abName : "") + "=false";
    if (set == "build" && abName) {
        // Builds of A and B in turn, \p repeats rounds of A B B A: the medians and the ratio
        // of the summed times.
        std::vector<double> ms[2];
        for (int k = 0; k < repeats; ++k)
            for (const int which : {0, 1, 1, 0}) {
                std::unique_ptr<Accel> accel = makeContender(which == 0);
                const double b0 = cpuNs();
                accel->build();
                ms[which].push_back((cpuNs() - b0) * 1e-6);
            }
        double sum[2] = {0, 0};
        for (int w = 0; w < 2; ++w) {
            for (double x : ms[w]) sum[w] += x;
            std::sort(ms[w].begin(), ms[w].end());
        }
        std::printf("build %s median %.2f ms, %s median %.2f ms, ratio %.3f (%zu builds each)\n", nameA.c_str(),
                    ms[0][ms[0].size() / 2], nameB.c_str(), ms[1][ms[1].size() / 2], sum[0] / sum[1], ms[0].size());
        return 0;
    }
    if (set == "build") {
        // The build alone, \p repeats times: the median thread CPU time (of Embree's default
        // mode with NORI_EMBREE, as the rays below).
        const bool ofEmbree = std::getenv("NORI_EMBREE") != nullptr;
        std::vector<double> ms;
        for (int k = 0; k < repeats; ++k) {
            std::unique_ptr<Accel> again;
            if (ofEmbree) {
                again = makeEmbree();
            } else {
                again = std::make_unique<OctreeAccel>(props);
                for (const Mesh *m : meshes) again->addMesh(m);
            }
            const double b0 = cpuNs();
            again->build();
            ms.push_back((cpuNs() - b0) * 1e-6);
        }
        std::sort(ms.begin(), ms.end());
        std::printf("%sbuild median %.2f ms (min %.2f) of %d\n", ofEmbree ? "embree: " : "", ms[ms.size() / 2], ms.front(),
                    repeats);
        return 0;
    }
    std::vector<Ray3f> primary = cameraRays(scene->camera(), spp, 0x6e6f7269u);
    ClosestHitFunction hit = [&](const Ray3f &r, Hit &h) { return octree.intersect(r, h); };
    std::vector<Ray3f> rays = set == "primary" ? primary
                              : set == "diffuse" ? diffuseRays(primary, hit, table, 0x62656e63u)
                                                 : lightShadowRays(primary, hit, table, lightAbove(table.bbox()));
    const bool shadow = set == "shadow";
    if (abName) {
        // A and B over the same rays in alternating slices (A B B A).
        std::unique_ptr<Accel> a = makeContender(true), b = makeContender(false);
        a->build();
        b->build();
        const Accel *order[4] = {a.get(), b.get(), b.get(), a.get()};
        double ns[2] = {0, 0};
        size_t found[2] = {0, 0};
        constexpr size_t kSlice = 8192;
        for (int k = 0; k < repeats; ++k)
            for (size_t first = 0; first < rays.size(); first += kSlice) {
                const size_t last = std::min(rays.size(), first + kSlice);
                for (const Accel *accel : order) {
                    const int which = accel == a.get() ? 0 : 1;
                    const double s0 = cpuNs();
                    for (size_t i = first; i < last; ++i) {
                        Hit h;
                        found[which] += shadow ? accel->occluded(rays[i]) : accel->intersect(rays[i], h);
                    }
                    ns[which] += cpuNs() - s0;
                }
            }
        std::printf("%s %.1f ns/ray, %s %.1f ns/ray, ratio %.3f", nameA.c_str(), ns[0] / (2.0 * rays.size() * repeats),
                    nameB.c_str(), ns[1] / (2.0 * rays.size() * repeats), ns[0] / ns[1]);
        if (abEmbree) {
            // (Embree's default mode misses or finds a few rays differently: not an error here.)
            std::printf(" (speed %.2fx Embree's; hits %zu and %zu)\n", ns[1] / ns[0], found[0], found[1]);
            return 0;
        }
        // Two octrees must agree on every ray.
        std::printf(" (%s)\n", found[0] == found[1] ? "same hits" : "HITS DIFFER");
        return found[0] == found[1] ? 0 : 1;
    }
    // NORI_EMBREE: the same rays through Embree's default mode (one thread).
    std::unique_ptr<Accel> embree;
    if (std::getenv("NORI_EMBREE")) {
        embree = makeEmbree();
        embree->build();
    }
    const Accel &timed = embree ? *embree : static_cast<const Accel &>(octree);
    size_t hits = 0;
    auto t2 = cpuNs();
    for (int k = 0; k < repeats; ++k)
        for (const Ray3f &r : rays) {
            Hit h;
            hits += shadow ? timed.occluded(r) : timed.intersect(r, h);
        }
    auto t3 = cpuNs();
    const double ns = (t3 - t2) / double(rays.size()) / repeats;
    std::printf("%sbuild %.1f ms, %zu %s rays x %d, %.1f %% hit, %.1f ns/ray\n", embree ? "embree: octree " : "",
                (t1 - t0) * 1e-6, rays.size(), set.c_str(), repeats,
                100.0 * double(hits) / double(rays.size()) / repeats, ns);
    if (argc > 5)
        for (const AccelStat &st : octree.statistics()) std::printf("%s %g\n", st.name.c_str(), st.value);
    return 0;
}
} // namespace

int main(int argc, char **argv) { return nori::bench::toolMain(argc, argv, run); }
