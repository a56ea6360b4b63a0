/// \file raytime.cpp
/// \brief nori-raytime: builds the default octree of a scene and traces one of the bench's ray
/// sets (primary, diffuse or shadow) repeatedly, for a profiler (perf, callgrind): no Embree.
#include "accel/octree.h"
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

int main(int argc, char **argv) {
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
    auto t0 = cpuNs();
    octree.build();
    auto t1 = cpuNs();
    if (set == "build") {
        // The build alone, \p repeats times: the median thread CPU time.
        std::vector<double> ms;
        for (int k = 0; k < repeats; ++k) {
            OctreeAccel again{props};
            for (const Mesh *m : meshes) again.addMesh(m);
            const double b0 = cpuNs();
            again.build();
            ms.push_back((cpuNs() - b0) * 1e-6);
        }
        std::sort(ms.begin(), ms.end());
        std::printf("build median %.2f ms (min %.2f) of %d\n", ms[ms.size() / 2], ms.front(), repeats);
        return 0;
    }
    std::vector<Ray3f> primary = cameraRays(scene->camera(), spp, 0x6e6f7269u);
    ClosestHitFunction hit = [&](const Ray3f &r, Hit &h) { return octree.intersect(r, h); };
    std::vector<Ray3f> rays = set == "primary" ? primary
                              : set == "diffuse" ? diffuseRays(primary, hit, table, 0x62656e63u)
                                                 : lightShadowRays(primary, hit, table, lightAbove(table.bbox()));
    const bool shadow = set == "shadow";
    size_t hits = 0;
    auto t2 = cpuNs();
    for (int k = 0; k < repeats; ++k)
        for (const Ray3f &r : rays) {
            Hit h;
            hits += shadow ? octree.occluded(r) : octree.intersect(r, h);
        }
    auto t3 = cpuNs();
    const double ns = (t3 - t2) / double(rays.size()) / repeats;
    std::printf("build %.1f ms, %zu %s rays x %d, %.1f %% hit, %.1f ns/ray\n",
                (t1 - t0) * 1e-6, rays.size(), set.c_str(), repeats,
                100.0 * double(hits) / double(rays.size()) / repeats, ns);
    if (argc > 5)
        for (const AccelStat &st : octree.statistics()) std::printf("%s %g\n", st.name.c_str(), st.value);
    return 0;
}
