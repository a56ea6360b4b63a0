/// \file raytime.cpp
/// \brief nori-raytime: builds the default octree of a scene and traces one of the bench's ray
/// sets (primary, diffuse or shadow) repeatedly, for a profiler (perf, callgrind).
/// Environment: NORI_LEAFSIZE=N sets leafSize; NORI_AB=PROP times the octree with the boolean
/// property PROP on against off, side by side in one run, and prints the ratio; NORI_EMBREE=1
/// times Embree's default mode on the same rays (or its build, for the set `build`) instead of
/// the octree (a peer for a profiler).
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
    const int repeats = argc > 3 ? std::atoi(argv[3]) : 10;
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
    if (const char *name = std::getenv("NORI_AB")) {
        // A/B in one process: the boolean property NORI_AB on (A) and off (B), over the same
        // rays in alternating slices (A B B A), so that the machine's drift hits both alike.
        PropertyList pa = props, pb = props;
        pa.setBoolean(name, true);
        pb.setBoolean(name, false);
        OctreeAccel a{pa}, b{pb};
        for (const Mesh *m : meshes) {
            a.addMesh(m);
            b.addMesh(m);
        }
        a.build();
        b.build();
        const OctreeAccel *order[4] = {&a, &b, &b, &a};
        double ns[2] = {0, 0};
        size_t found[2] = {0, 0};
        constexpr size_t kSlice = 8192;
        for (int k = 0; k < repeats; ++k)
            for (size_t first = 0; first < rays.size(); first += kSlice) {
                const size_t last = std::min(rays.size(), first + kSlice);
                for (const OctreeAccel *accel : order) {
                    const int which = accel == &a ? 0 : 1;
                    const double s0 = cpuNs();
                    for (size_t i = first; i < last; ++i) {
                        Hit h;
                        found[which] += shadow ? accel->occluded(rays[i]) : accel->intersect(rays[i], h);
                    }
                    ns[which] += cpuNs() - s0;
                }
            }
        std::printf("%s=true %.1f ns/ray, %s=false %.1f ns/ray, ratio %.3f (%s)\n", name, ns[0] / (2.0 * rays.size() * repeats),
                    name, ns[1] / (2.0 * rays.size() * repeats), ns[0] / ns[1], found[0] == found[1] ? "same hits" : "HITS DIFFER");
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
