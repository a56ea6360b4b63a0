/// \file sahref.cpp
/// \brief nori-sahref: the work per ray of a reference tree, a surface-area-heuristic BVH built by
/// Embree's own builder (rtcBuildBVH: binned SAH, up to eight children), on the bench's primary,
/// diffuse and shadow rays. Embree does not count its traversal's steps; this tree, traversed
/// front to back as Embree traverses its BVH8, says how many node visits, leaves and triangle
/// tests a SAH tree of Embree's kind needs on the same rays, next to the octree's counts
/// (nori-raydiag SCENE 1 -1 in a -DNORI_OCTREE_COUNTERS build).
#include "accel/octree.h"
#include "tool_main.h"
#include <embree3/rtcore.h>
#include <ray_sets.h>
#include <scene_geometry.h>
#include <nori/camera.h>
#include <nori/mesh.h>
#include <nori/objloader.h>
#include <nori/scene.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

using namespace nori;

namespace {

/// A node of the reference tree: up to eight children, each an inner node or a leaf. Leaves are
/// told apart by the low bit of their address (the builder hands children back as given).
struct RefNode {
    float lo[3][8], hi[3][8];
    const void *child[8];
    int n;
};
/// A leaf: its triangle count, then that many global triangle ids.
struct RefLeaf {
    uint32_t n;
    uint32_t prims[1];
};

/// The reference tree; nodes and leaves live in the RTCBVH's memory (freed with it).
struct RefTree {
    std::vector<std::array<Eigen::Vector3d, 3>> tris;
    RTCDevice device = nullptr;
    RTCBVH bvh = nullptr;
    const void *root = nullptr;
    size_t nodes = 0, leaves = 0;  ///< counted by the build's callbacks (a one-thread device)

    RefTree() = default;
    RefTree(const RefTree &) = delete;
    RefTree &operator=(const RefTree &) = delete;
    ~RefTree() {
        if (bvh) rtcReleaseBVH(bvh);
        if (device) rtcReleaseDevice(device);
    }
};

/// Work of one ray.
struct Work {
    double nodes = 0, leaves = 0, tris = 0, blocks = 0;  ///< blocks: of four triangles (Embree's Triangle4)
};

/// Möller–Trumbore in double: t of a hit within [mint, maxt], or a negative number.
double hitT(const std::array<Eigen::Vector3d, 3> &v, const Eigen::Vector3d &o, const Eigen::Vector3d &d, double mint, double maxt) {
    const Eigen::Vector3d e1 = v[1] - v[0], e2 = v[2] - v[0], p = d.cross(e2);
    const double det = e1.dot(p);
    if (det == 0.0) return -1.0;
    const Eigen::Vector3d s = o - v[0];
    const double u = s.dot(p) / det;
    if (u < 0.0 || u > 1.0) return -1.0;
    const Eigen::Vector3d q = s.cross(e1);
    const double w = d.dot(q) / det;
    if (w < 0.0 || u + w > 1.0) return -1.0;
    const double t = e2.dot(q) / det;
    return t >= mint && t <= maxt ? t : -1.0;
}

/// Front-to-back traversal of the reference tree (children by entry distance, nearest first,
/// those entered beyond the closest hit culled); \p anyHit stops at the first hit.
bool traverse(const RefTree &tree, const Ray3f &ray, bool anyHit, Work &w) {
    const Eigen::Vector3d o = ray.o.cast<double>(), d = ray.d.cast<double>();
    double best = ray.maxt;
    bool found = false;
    struct Entry {
        const void *ptr;
        bool leaf;
        double t;
    };
    auto entry = [](const void *p, double t) {  // (the low bit marks a leaf)
        const auto bits = reinterpret_cast<uintptr_t>(p);
        return Entry{reinterpret_cast<const void *>(bits & ~uintptr_t(1)), bool(bits & 1u), t};
    };
    std::vector<Entry> stack{entry(tree.root, ray.mint)};
    while (!stack.empty()) {
        Entry e = stack.back();
        stack.pop_back();
        if (e.t > best) continue;
        if (e.leaf) {
            const auto *leaf = static_cast<const RefLeaf *>(e.ptr);
            w.leaves += 1;
            w.blocks += double((leaf->n + 3) / 4);
            for (uint32_t i = 0; i < leaf->n; ++i) {
                const uint32_t p = leaf->prims[i];
                w.tris += 1;
                const double t = hitT(tree.tris[p], o, d, ray.mint, best);
                if (t >= 0.0) {
                    best = t;
                    found = true;
                    if (anyHit) return true;
                }
            }
            continue;
        }
        const auto *node = static_cast<const RefNode *>(e.ptr);
        w.nodes += 1;
        Entry hits[8];
        int k = 0;
        for (int c = 0; c < node->n; ++c) {
            double t0 = ray.mint, t1 = best;
            for (int a = 0; a < 3; ++a) {
                const double r = 1.0 / d[a];
                double tn = (node->lo[a][c] - o[a]) * r, tf = (node->hi[a][c] - o[a]) * r;
                if (tn > tf) std::swap(tn, tf);
                if (tn > t0) t0 = tn;  // (a NaN, 0 * inf on a slab plane, never narrows)
                if (tf < t1) t1 = tf;
            }
            if (t0 <= t1) hits[k++] = entry(node->child[c], t0);
        }
        // Farthest first onto the stack, so that the nearest is popped next (insertion sort).
        for (int i = 1; i < k; ++i)
            for (int j = i; j > 0 && hits[j - 1].t < hits[j].t; --j) std::swap(hits[j - 1], hits[j]);
        for (int i = 0; i < k; ++i) stack.push_back(hits[i]);
    }
    return found;
}

/// Builds the reference over every triangle of \p meshes into \p tree: Embree's binned SAH
/// builder (medium quality, as Embree's default scenes), up to eight children per node,
/// leaves of at most \p maxLeaf triangles priced in blocks of \p blockSize.
void buildReference(const std::vector<const Mesh *> &meshes, unsigned blockSize, unsigned maxLeaf, RefTree &tree) {
    for (const Mesh *m : meshes)
        for (uint32_t f = 0; f < m->triangleCount(); ++f)
            tree.tris.push_back({m->vertex(f, 0).cast<double>(), m->vertex(f, 1).cast<double>(), m->vertex(f, 2).cast<double>()});
    std::vector<RTCBuildPrimitive> prims(tree.tris.size());
    for (size_t i = 0; i < prims.size(); ++i) {
        const auto &t = tree.tris[i];
        const Eigen::Vector3d lo = t[0].cwiseMin(t[1]).cwiseMin(t[2]), hi = t[0].cwiseMax(t[1]).cwiseMax(t[2]);
        prims[i] = {float(lo.x()), float(lo.y()), float(lo.z()), 0, float(hi.x()), float(hi.y()), float(hi.z()), unsigned(i)};
    }
    tree.device = rtcNewDevice("threads=1");
    if (!tree.device) throw NoriException("nori-sahref: rtcNewDevice failed");
    tree.bvh = rtcNewBVH(tree.device);
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    args.maxBranchingFactor = 8;
    args.maxDepth = 1024;
    args.sahBlockSize = blockSize;
    args.minLeafSize = 1;
    args.maxLeafSize = maxLeaf;
    args.traversalCost = 1.0f;
    args.intersectionCost = 1.0f;
    args.bvh = tree.bvh;
    args.primitives = prims.data();
    args.primitiveCount = prims.size();
    args.primitiveArrayCapacity = prims.size();
    args.userPtr = &tree;
    args.createNode = [](RTCThreadLocalAllocator alloc, unsigned n, void *user) -> void * {
        auto *node = static_cast<RefNode *>(rtcThreadLocalAlloc(alloc, sizeof(RefNode), alignof(RefNode)));
        node->n = int(n);
        ++static_cast<RefTree *>(user)->nodes;
        return node;
    };
    args.setNodeChildren = [](void *ptr, void **children, unsigned n, void *) {
        auto *node = static_cast<RefNode *>(ptr);
        for (unsigned c = 0; c < n; ++c) node->child[c] = children[c];
    };
    args.setNodeBounds = [](void *ptr, const RTCBounds **bounds, unsigned n, void *) {
        auto *node = static_cast<RefNode *>(ptr);
        for (unsigned c = 0; c < n; ++c) {
            node->lo[0][c] = bounds[c]->lower_x, node->lo[1][c] = bounds[c]->lower_y, node->lo[2][c] = bounds[c]->lower_z;
            node->hi[0][c] = bounds[c]->upper_x, node->hi[1][c] = bounds[c]->upper_y, node->hi[2][c] = bounds[c]->upper_z;
        }
    };
    args.createLeaf = [](RTCThreadLocalAllocator alloc, const RTCBuildPrimitive *p, size_t n, void *user) -> void * {
        const size_t bytes = sizeof(RefLeaf) + sizeof(uint32_t) * (n ? n - 1 : 0);
        auto *leaf = static_cast<RefLeaf *>(rtcThreadLocalAlloc(alloc, bytes, alignof(RefLeaf)));
        leaf->n = uint32_t(n);
        for (size_t i = 0; i < n; ++i) leaf->prims[i] = p[i].primID;
        ++static_cast<RefTree *>(user)->leaves;
        return reinterpret_cast<void *>(reinterpret_cast<uintptr_t>(leaf) | 1u);
    };
    tree.root = rtcBuildBVH(&args);
    if (!tree.root) throw NoriException("nori-sahref: rtcBuildBVH failed ({} triangles)", prims.size());
}

/// A whole positive number from argument \p name.
unsigned positiveArg(const char *text, const char *name) {
    char *end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (!end || *end || v < 1 || v > 1000000) throw NoriException("nori-sahref: {} must be a whole number >= 1 (got '{}')", name, text);
    return unsigned(v);
}

int run(int argc, char **argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: nori-sahref SCENE.xml|MESH.obj[.gz] [spp (1)] [sah block size (4)] [max leaf (16)]\n"
                             "  work per ray of a SAH BVH8 built by Embree, and (in a -DNORI_OCTREE_COUNTERS build) the octree's\n");
        return 2;
    }
    // Defaults: one ray per pixel (as nori-raydiag's counts), leaves priced in blocks of four
    // triangles and holding at most sixteen (Embree's BVH8 over Triangle4 leaves).
    const int spp = argc > 2 ? int(positiveArg(argv[2], "spp")) : 1;
    const unsigned block = argc > 3 ? positiveArg(argv[3], "sah block size") : 4;
    const unsigned maxLeaf = argc > 4 ? positiveArg(argv[4], "max leaf") : 16;
    // A scene (its meshes and camera), or one OBJ mesh seen by nori-bench's framing camera
    // (512 x 512, as its mesh rows).
    const std::string input = argv[1];
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Mesh> objMesh;
    std::unique_ptr<Camera> framing;
    std::vector<const Mesh *> meshes;
    auto endsWith = [&](const char *tail) {
        const std::string t = tail;
        return input.size() > t.size() && input.compare(input.size() - t.size(), t.size(), t) == 0;
    };
    if (endsWith(".obj") || endsWith(".obj.gz")) {
        objMesh = std::make_unique<Mesh>(loadObjFile(input), "mesh");
        meshes.push_back(objMesh.get());
    } else {
        scene = loadSceneGeometry(input);
        for (const auto &m : scene->meshes()) meshes.push_back(m.get());
    }
    MeshTable table(meshes);
    if (table.triangleCount() == 0) throw NoriException("{}: no triangles", input);
    if (objMesh) framing = framingCamera(table.bbox(), 512, 512);
    const Camera &camera = objMesh ? *framing : scene->camera();
    RefTree tree;
    buildReference(meshes, block, maxLeaf, tree);
    std::printf("reference SAH tree (block %u, max leaf %u): %zu nodes, %zu leaves, %zu triangles\n", block, maxLeaf,
                tree.nodes, tree.leaves, tree.tris.size());
    // The ray sets of nori-raydiag (the same seeds, hit points from the octree).
    OctreeAccel octree{PropertyList()};
    for (const Mesh *m : meshes) octree.addMesh(m);
    octree.build();
    ClosestHitFunction octHit = [&](const Ray3f &r, Hit &h) { return octree.intersect(r, h); };
    std::vector<Ray3f> primary = cameraRays(camera, spp, 0x6e6f7269u);
    std::vector<Ray3f> diffuse = diffuseRays(primary, octHit, table, 0x62656e63u);
    std::vector<Ray3f> shadow = lightShadowRays(primary, octHit, table, lightAbove(table.bbox()));
    auto report = [&](const char *name, const std::vector<Ray3f> &rays, bool anyHit) {
        Work w;
        size_t hits = 0, octreeHits = 0;
        for (const Ray3f &r : rays) hits += traverse(tree, r, anyHit, w);
        const double n = double(std::max<size_t>(rays.size(), 1));
        std::printf("%-8s %8zu rays %5.1f%% hit | reference: nodes %.2f, leaves %.2f, triangles %.2f in %.2f blocks of 4",
                    name, rays.size(), 100.0 * double(hits) / n, w.nodes / n, w.leaves / n, w.tris / n, w.blocks / n);
#ifdef NORI_OCTREE_COUNTERS
        // The octree's work on the same rays (a measuring build).
        g_octreeCounters = {};
        for (const Ray3f &r : rays) {
            Hit h;
            octreeHits += anyHit ? octree.occluded(r) : octree.intersect(r, h);
        }
        const OctreeCounters &c = g_octreeCounters;
        std::printf(" | octree: nodes %.2f, lists %.2f (kept %.2f), triangles %.2f in %.2f chunks",
                    double(c.nodes) / n, double(c.leaves + c.keptLists) / n, double(c.keptLists) / n,
                    double(c.leafTris + c.keptTris) / n, double(c.chunks) / n);
        if (octreeHits != hits) std::printf(" (octree: %zu hits)", octreeHits);
#endif
        (void)octreeHits;
        std::printf("\n");
    };
    report("primary", primary, false);
    report("diffuse", diffuse, false);
    report("shadow", shadow, true);
    return 0;
}

} // namespace

int main(int argc, char **argv) { return nori::bench::toolMain(argc, argv, run); }
