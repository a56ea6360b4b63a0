/// \file raydiag.cpp
/// \brief nori-raydiag: the diffuse rays of a bench case that the octree and Embree robust
/// answer differently, one line each, with the surface each ray leaves.
#include "accel/octree.h"
#include "tool_main.h"
#include <embree_oracle.h>
#include <oracle_judge.h>
#include <ray_sets.h>
#include <scene_geometry.h>
#include <scene_generator.h>
#include <nori/objloader.h>
#include <pcg_random.hpp>
#include <cstdio>
#include <cstdlib>
#include <tuple>
#include <algorithm>

using namespace nori;

namespace {
/// Exact (double) t of the ray on the plane of triangle f.
double exactT(const Mesh &m, uint32_t f, const Ray3f &ray) {
    Eigen::Vector3d a = m.vertex(f, 0).cast<double>(), b = m.vertex(f, 1).cast<double>(), c = m.vertex(f, 2).cast<double>();
    Eigen::Vector3d n = (b - a).cross(c - a);
    return n.dot(a - ray.o.cast<double>()) / n.dot(ray.d.cast<double>());
}
double planeDistance(const Mesh &m, uint32_t f, const Point3f &p) {
    Eigen::Vector3d a = m.vertex(f, 0).cast<double>(), b = m.vertex(f, 1).cast<double>(), c = m.vertex(f, 2).cast<double>();
    Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    return n.dot(p.cast<double>() - a);
}
} // namespace

namespace {
int run(int argc, char **argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: nori-raydiag SCENE.xml|shape:NAME [spp] [max lines (-1: work per ray, counters build)] [primary]\n"
                     "       nori-raydiag SCENE.xml|shape:NAME --leaves   (the largest leaves)\n");
        return 2;
    }
    std::string input = argv[1];
    int spp = argc > 2 ? std::atoi(argv[2]) : 4;
    int maxLines = argc > 3 ? std::atoi(argv[3]) : 50;
    std::unique_ptr<Scene> scene;
    std::vector<std::unique_ptr<Mesh>> owned;
    std::unique_ptr<Camera> ownedCamera;
    std::vector<const Mesh *> meshes;
    const Camera *camera;
    if (input.rfind("shape:", 0) == 0) {
        gen::GeneratedScene g = gen::generateScene(input.substr(6));
        ownedCamera = gen::makeCamera(g.camera);
        owned.push_back(std::make_unique<Mesh>(std::move(g.mesh), "gen"));
        meshes.push_back(owned.back().get());
        camera = ownedCamera.get();
    } else {
        scene = loadSceneGeometry(input);
        for (const auto &m : scene->meshes()) meshes.push_back(m.get());
        camera = &scene->camera();
    }
    MeshTable table(meshes);
    EmbreeOracle robust(meshes, {true, 1}), fast(meshes, {false, 1});
    PropertyList octreeProps;  // NORI_FOLD=0: without wide nodes
    if (const char *f = std::getenv("NORI_FOLD")) octreeProps.setBoolean("fold", std::string(f) != "0");
    OctreeAccel octree{octreeProps};
    for (const Mesh *m : meshes) octree.addMesh(m);
    octree.build();

    if (argc >= 3 && std::string(argv[2]) == "--leaves") {
        // The largest leaves: triangles, depth, box extents (the scene's in the first line).
        std::vector<std::tuple<uint32_t, int, Vector3f>> leaves;
        octree.forEachNode([&](const OctreeAccel::NodeView &v) {
            for (int c = 0; c < 8; ++c) {
                const uint32_t n = v.node.count[c];
                if (!n || (n & OctreeNode::kInner)) continue;
                leaves.emplace_back(n, v.depth + 1,
                                    Vector3f(v.node.box[0][8 + c] - v.node.box[0][c], v.node.box[1][8 + c] - v.node.box[1][c],
                                             v.node.box[2][8 + c] - v.node.box[2][c]));
            }
        });
        std::sort(leaves.begin(), leaves.end(), [](const auto &a, const auto &b) { return std::get<0>(a) > std::get<0>(b); });
        const Vector3f e = table.bbox().extents();
        std::printf("scene extents %g %g %g, %zu leaves\n", e.x(), e.y(), e.z(), leaves.size());
        for (size_t i = 0; i < std::min<size_t>(leaves.size(), 15); ++i)
            std::printf("%u triangles, depth %d, box %g %g %g\n", std::get<0>(leaves[i]), std::get<1>(leaves[i]),
                        std::get<2>(leaves[i]).x(), std::get<2>(leaves[i]).y(), std::get<2>(leaves[i]).z());
        return 0;
    }
    if (argc >= 9 && std::string(argv[2]) == "--probe") {
        // One ray given as hex floats: every intersector's answer and the exact t on each plane hit.
        Ray3f ray(Point3f(std::strtof(argv[3], nullptr), std::strtof(argv[4], nullptr), std::strtof(argv[5], nullptr)),
                  Vector3f(std::strtof(argv[6], nullptr), std::strtof(argv[7], nullptr), std::strtof(argv[8], nullptr)),
                  0.0f, argc > 9 ? std::strtof(argv[9], nullptr) : Infinity);
        PropertyList mtProps;
        mtProps.setString("intersector", "mt");
        OctreeAccel mt(mtProps);
        for (const Mesh *m : meshes) mt.addMesh(m);
        mt.build();
        const char *names[] = {"octree watertight", "octree mt", "embree robust", "embree default"};
        for (int k = 0; k < 4; ++k) {
            Hit h;
            bool hit = k == 0 ? octree.intersect(ray, h) : k == 1 ? mt.intersect(ray, h) : k == 2 ? robust.intersect(ray, h)
                                                                                              : fast.intersect(ray, h);
            if (!hit) {
                std::printf("%-18s miss\n", names[k]);
                continue;
            }
            auto [hm, hf] = octree.locate(h.prim);
            Eigen::Vector3d a = hm->vertex(hf, 0).cast<double>(), b = hm->vertex(hf, 1).cast<double>(),
                            c = hm->vertex(hf, 2).cast<double>();
            Eigen::Vector3d n = (b - a).cross(c - a).normalized();
            double te = exactT(*hm, hf, ray);
            double sinAngle = std::abs(n.dot(ray.d.cast<double>().normalized()));
            std::printf("%-18s t %.9g prim %u (u %.7g v %.7g) | exact t %.9g, error %.3g (%.3g relative), sin(angle to "
                        "plane) %.3g, max |v - o| %.3g\n",
                        names[k], h.t, h.prim, h.u, h.v, te, h.t - te, (h.t - te) / te, sinAngle,
                        std::max({(a - ray.o.cast<double>()).norm(), (b - ray.o.cast<double>()).norm(),
                                  (c - ray.o.cast<double>()).norm()}));
            for (int k = 0; k < 3; ++k)
                std::printf("    v%d (%a, %a, %a)\n", k, hm->vertex(hf, k).x(), hm->vertex(hf, k).y(), hm->vertex(hf, k).z());
        }
        return 0;
    }
    std::vector<Ray3f> primary = cameraRays(*camera, spp, 0x6e6f7269u);
#ifdef NORI_OCTREE_COUNTERS
    if (maxLines < 0) {
        // Work per ray of the octree's default traversal (a measuring build: -DNORI_OCTREE_COUNTERS).
        ClosestHitFunction octHit = [&](const Ray3f &r, Hit &h) { return octree.intersect(r, h); };
        std::vector<Ray3f> diffuseSet = diffuseRays(primary, octHit, table, 0x62656e63u);
        std::vector<Ray3f> shadowSet = lightShadowRays(primary, octHit, table, lightAbove(table.bbox()));
        for (const AccelStat &s : octree.statistics()) std::printf("%s %g\n", s.name.c_str(), s.value);
        // Per-node counters, one slot per inner node (indices as in forEachNode).
        size_t innerNodes = 0;
        octree.forEachNode([&](const OctreeAccel::NodeView &v) { innerNodes = std::max<size_t>(innerNodes, v.index + 1); });
        auto report = [&](const char *name, const std::vector<Ray3f> &rays, bool shadow) {
            g_octreeCounters = {};
            std::vector<uint64_t> visits(innerNodes, 0), emptyVisits(innerNodes, 0);
            g_octreeCounters.nodeVisits = &visits;
            g_octreeCounters.emptyVisits = &emptyVisits;
            size_t hits = 0;
            for (const Ray3f &r : rays) {
                Hit h;
                hits += shadow ? octree.occluded(r) : octree.intersect(r, h);
            }
            double n = double(std::max<size_t>(rays.size(), 1));
            std::printf("%-8s %8zu rays %5.1f%% hit | per ray: nodes %.2f (wide %.2f), kept tris %.2f, leaves %.2f, leaf tris %.2f, chunks %.2f, exact t %.3f\n",
                        name, rays.size(), 100.0 * double(hits) / n, double(g_octreeCounters.nodes) / n,
                        double(g_octreeCounters.wideNodes) / n, double(g_octreeCounters.keptTris) / n, double(g_octreeCounters.leaves) / n,
                        double(g_octreeCounters.leafTris) / n, double(g_octreeCounters.chunks) / n,
                        double(g_octreeCounters.exactT) / n);
            std::printf("         kernel steps %.2f, with a lane inside a triangle %.2f, with a hit in range %.2f\n",
                        double(g_octreeCounters.steps) / n, double(g_octreeCounters.stepsInside) / n,
                        double(g_octreeCounters.stepsHit) / n);
            std::printf("         kept lists %.2f, their chunks %.2f | leaves/chunks by leaf size (<=16, 32, 64, 128, 256, more):",
                        double(g_octreeCounters.keptLists) / n, double(g_octreeCounters.keptChunks) / n);
            for (int b = 0; b < 6; ++b)
                std::printf(" %.2f/%.2f", double(g_octreeCounters.leavesBySize[b]) / n, double(g_octreeCounters.chunksBySize[b]) / n);
            std::printf("\n         kept lists/chunks by list size (<=4, 16, 64, 256, more):");
            for (int b = 0; b < 5; ++b)
                std::printf(" %.2f/%.2f", double(g_octreeCounters.keptBySize[b]) / n, double(g_octreeCounters.keptChunksBySize[b]) / n);
            std::printf("\n");
            // Visits by depth, and by the node's filled children.
            std::vector<double> byDepth(40, 0.0), byFilled(OctreeWideNode::kSlots + 1, 0.0);
            std::vector<double> emptyByDepth(40, 0.0), emptyByFilled(OctreeWideNode::kSlots + 1, 0.0);
            octree.forEachNode([&](const OctreeAccel::NodeView &v) {
                int filled = 0;
                for (int c = 0; c < 8; ++c) filled += v.node.box[0][c] <= v.node.box[0][8 + c];
                byDepth[std::min(v.depth, 39)] += double(visits[v.index]);
                byFilled[filled] += double(visits[v.index]);
                emptyByDepth[std::min(v.depth, 39)] += double(emptyVisits[v.index]);
                emptyByFilled[filled] += double(emptyVisits[v.index]);
            });
            std::printf("         node visits by depth:");
            for (int d = 0; d < 40; ++d)
                if (byDepth[d] > 0) std::printf(" %d:%.2f", d, byDepth[d] / n);
            std::printf("\n         by filled children:");
            for (int f = 0; f <= OctreeWideNode::kSlots; ++f) std::printf(" %d:%.2f", f, byFilled[f] / n);
            std::printf("\n         by children entered:");
            for (int f = 0; f <= OctreeWideNode::kSlots; ++f) std::printf(" %d:%.2f", f, double(g_octreeCounters.entered[f]) / n);
            std::printf("\n         entering no child, by depth:");
            for (int d = 0; d < 40; ++d)
                if (emptyByDepth[d] > 0) std::printf(" %d:%.2f", d, emptyByDepth[d] / n);
            std::printf("\n         entering no child, by filled children:");
            for (int f = 0; f <= 8; ++f) std::printf(" %d:%.2f", f, emptyByFilled[f] / n);
            std::printf("\n");
        };
        report("primary", primary, false);
        report("diffuse", diffuseSet, false);
        report("shadow", shadowSet, true);
        return 0;
    }
#endif
    ClosestHitFunction hitFn = [&](const Ray3f &r, Hit &h) { return robust.intersect(r, h); };
    // argv[4] == "primary": the camera rays themselves (the bench's primary set) instead.
    const bool primaryMode = argc > 4 && std::string(argv[4]) == "primary";
    std::vector<Ray3f> diffuse = primaryMode ? primary : diffuseRays(primary, hitFn, table, 0x62656e63u);
    // The surface each diffuse ray leaves: the primary hits in order, as diffuseRays takes them.
    std::vector<Hit> sources;
    for (const Ray3f &r : primary) {
        Hit h;
        if (!robust.intersect(r, h)) continue;
        Point3f p;
        Normal3f n;
        float offset;
        table.surface(h.prim, h.u, h.v, p, n, offset);
        if (n.isZero()) continue;
        sources.push_back(h);
    }
    if (primaryMode) sources.assign(diffuse.size(), Hit{});
    if (sources.size() != diffuse.size()) {
        std::fprintf(stderr, "internal: %zu sources for %zu rays\n", sources.size(), diffuse.size());
        return 1;
    }
    OracleJudge judge(meshes);
    std::array<size_t, VerdictCount> verdicts{};
    size_t mism = 0, fastMism = 0;
    // Exact referee over every ray where any two of the three answers differ: right / wrong /
    // undecidable counts for octree, robust, fast.
    size_t disputed = 0, right[3] = {}, wrong[3] = {};
    for (size_t i = 0; i < diffuse.size(); ++i) {
        const Ray3f &ray = diffuse[i];
        Hit ho, hr, hf;
        bool o = octree.intersect(ray, ho), r = robust.intersect(ray, hr), f = fast.intersect(ray, hf);
        auto differs = [&](bool a, const Hit &ha) {
            if (a != r) return true;
            if (!a) return false;
            return std::abs(double(ha.t) - double(hr.t)) / std::max(std::abs(double(hr.t)), 1e-30) > 1e-4;
        };
        fastMism += differs(f, hf);
        if (differs(o, ho) || differs(f, hf)) {
            ++disputed;
            std::vector<uint32_t> cand;
            for (auto [a, h] : {std::pair<bool, const Hit *>{o, &ho}, {r, &hr}, {f, &hf}})
                if (a) cand.push_back(h->prim);
            int k = 0;
            for (auto [a, h] : {std::pair<bool, const Hit *>{o, &ho}, {r, &hr}, {f, &hf}}) {
                int v = judge.referee(ray, a, *h, cand);
                right[k] += v > 0;
                wrong[k] += v < 0;
                ++k;
            }
        }
        if (!differs(o, ho)) continue;
        ++mism;
        Verdict v = judge.judge(ray, o, ho, r, hr);
        ++verdicts[v];
        if (int(mism) > maxLines) continue;
        auto [sm, sf] = octree.locate(primaryMode ? (r ? hr.prim : ho.prim) : sources[i].prim);
        double scale = std::max(double(ray.o.cwiseAbs().maxCoeff()), double((r ? hr.t : ho.t) * ray.d.norm()));
        double ulp = std::ldexp(1.0, std::ilogb(scale) - 23);  // one float ulp at the scale
        std::string exact;
        if (o && r && ho.prim == hr.prim) {
            auto [hm, hf] = octree.locate(hr.prim);
            double te = exactT(*hm, hf, ray), dn = ray.d.cast<double>().norm();
            exact = fmt::format(" | exact t {:.9g}: |err| octree {:.2f} ulp, robust {:.2f} ulp of scale {:.3g}", te,
                                std::abs(ho.t - te) * dn / ulp, std::abs(hr.t - te) * dn / ulp, scale);
        }
        std::printf("[%s] ray %zu src %u (dist of origin to src plane %.3g, |o| %.3g) | octree %s t %.9g prim %u | robust %s t "
                    "%.9g prim %u | fast %s t %.9g prim %u%s\n",
                    verdictName(v), i, sources[i].prim, planeDistance(*sm, sf, ray.o), double(ray.o.cwiseAbs().maxCoeff()),
                    o ? "hit" : "miss", ho.t, ho.prim, r ? "hit" : "miss", hr.t, hr.prim, f ? "hit" : "miss", hf.t,
                    hf.prim, exact.c_str());
    }
    std::printf("%zu %s rays: octree %zu mismatches, embree default %zu; octree's by verdict:", diffuse.size(), primaryMode ? "primary" : "diffuse", mism,
                fastMism);
    for (int v = 0; v < VerdictCount; ++v) std::printf(" %s %zu", verdictName(v), verdicts[size_t(v)]);
    std::printf("\n");
    std::printf("exact referee on the %zu rays where an answer differs from robust's: right/wrong (rest undecidable): "
                "octree %zu/%zu, embree robust %zu/%zu, embree default %zu/%zu\n",
                disputed, right[0], wrong[0], right[1], wrong[1], right[2], wrong[2]);
    return 0;
}
} // namespace

int main(int argc, char **argv) { return nori::bench::toolMain(argc, argv, run); }
