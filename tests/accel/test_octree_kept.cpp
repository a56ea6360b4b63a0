/// \file test_octree_kept.cpp
/// \brief The octree's kept groups: large triangles a node keeps instead of copying them into
/// its children are grouped by where they lie, each group with its own box, and the
/// traversals still give brute force's answers with several groups per node.
#include <gtest/gtest.h>
#include "accel/octree.h"
#include "robust_util.h"
#include <map>
#include <pcg_random.hpp>

using namespace nori;
using namespace nori::robust;

namespace {

std::map<std::string, double> statsOf(const Accel &accel) {
    std::map<std::string, double> s;
    for (const AccelStat &st : accel.statistics()) s[st.name] = st.value;
    return s;
}

std::unique_ptr<Accel> buildOctree(const std::vector<const Mesh *> &meshes, const char *traversal = "simd") {
    PropertyList p;
    p.setString("traversal", traversal);
    return makeAccel("octree", p, meshes);
}

/// Append \p part to \p out.
void append(MeshData &out, const MeshData &part) {
    const uint32_t base = uint32_t(out.positions.size());
    out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
    for (auto f : part.faces) out.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
}

/// The quad [x0, x1] x [z0, z1] at height y (two triangles).
MeshData quadAt(float x0, float x1, float z0, float z1, float y) {
    MeshData q;
    q.positions = {Point3f(x0, y, z0), Point3f(x1, y, z0), Point3f(x1, y, z1), Point3f(x0, y, z1)};
    q.faces = {{0, 1, 2}, {0, 2, 3}};
    return q;
}

/// Height of TableScene's ceiling.
constexpr float kCeiling = 18.0f;

/// A table-like scene (pa5's table: small objects on a ground quad, a large light quad high
/// above): 16 x 16 small boxes (each face tessellated \p n x n) on a ground quad at y = 0 and
/// a ceiling quad at y = kCeiling about as wide as the ground.
struct TableScene {
    MeshData objects, ground, ceiling;
    explicit TableScene(int n) {
        for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j)
                append(objects, scaled(cube(n), 0.3f, Vector3f(-10.0f + 20.0f * i / 15.0f, 0.3f, -10.0f + 20.0f * j / 15.0f)));
        ground = quadAt(-12.0f, 12.0f, -12.0f, 12.0f, 0.0f);
        ceiling = quadAt(-11.0f, 13.0f, -10.0f, 11.0f, kCeiling);
    }
};

/// Every answer of \p octree (closest hit: found, triangle, t; any hit) on \p rays against
/// brute force's; returns the rays that differ (and counts brute force's hits in \p hits).
size_t differences(const Accel &octree, const Accel &brute, const std::vector<Ray3f> &rays, size_t &hits) {
    size_t differ = 0;
    hits = 0;
    for (const Ray3f &ray : rays) {
        Hit a, b;
        const bool fa = octree.intersect(ray, a), fb = brute.intersect(ray, b);
        hits += fb;
        const bool same = fa == fb && (!fa || (a.prim == b.prim && a.t == b.t)) && octree.occluded(ray) == brute.occluded(ray);
        if (!same && ++differ <= 3)
            std::printf("[kept] octree %d t %.9g prim %u, brute %d t %.9g prim %u\n", int(fa), a.t, a.prim, int(fb), b.t, b.prim);
    }
    return differ;
}

} // namespace

// The ground and the ceiling are both large enough to stay high in the tree instead of being
// copied into every cell along them, but they lie 18 apart: one box around both is the whole
// scene, entered by every ray (a shadow ray from a box towards a light between them would
// test both quads). They must be kept in separate groups, each in its own flat box. Before
// kept groups, the root kept all four triangles in one list whose box was the scene's,
// (-12, 0, -12) - (13, 18, 12) (so it did with the ceiling at 16 to 20).
TEST(OctreeKeptGroups, AGroundAndACeilingAreKeptInSeparateBoxes) {
    TableScene s(4);
    Mesh objects(s.objects, "boxes"), ground(s.ground, "ground"), ceiling(s.ceiling, "ceiling");
    auto octree = buildOctree({&objects, &ground, &ceiling});
    auto st = statsOf(*octree);
    size_t spanning = 0, groups = 0;
    std::vector<OctreeKept> root;
    dynamic_cast<const OctreeAccel &>(*octree).forEachNode([&](const OctreeAccel::NodeView &v) {
        uint32_t total = 0;
        for (const OctreeKept &g : v.keptGroups()) {
            ++groups;
            total += g.count;
            EXPECT_LE(g.lo[1], g.hi[1]);
            if (g.lo[1] <= 0.0f && g.hi[1] >= kCeiling) ++spanning;  // holds part of both quads
        }
        EXPECT_EQ(total, v.ref & OctreeNode::kKeptMask);  // the groups hold the node's kept triangles
        EXPECT_LE(v.keptGroups().size(), size_t(OctreeKept::kMaxGroups));
        if (v.depth == 0) root = v.keptGroups();
    });
    std::printf("[kept] ground and ceiling: %zu kept groups (%zu at the root), %zu spanning both; refs %.0f, kept %.0f\n",
                groups, root.size(), spanning, st["triangle_refs"], st["kept_refs"]);
    EXPECT_EQ(spanning, 0u);
    EXPECT_EQ(double(groups), st["kept_groups"]);
    // Both quads stay at the root, neither copied along the cells: two groups of two
    // triangles, each in the quad's own flat box.
    ASSERT_EQ(root.size(), 2u);
    for (const OctreeKept &g : root) {
        EXPECT_EQ(g.count, 2u);
        EXPECT_EQ(g.lo[1], g.hi[1]);
        EXPECT_TRUE(g.lo[1] == 0.0f || g.lo[1] == kCeiling) << g.lo[1];
    }
    EXPECT_NE(root[0].lo[1], root[1].lo[1]);
}

// With several kept groups per node, every traversal still gives brute force's answers: the
// simd closest-hit traversal tests a group at once when its box comes before the nearest
// child and otherwise puts it among the waiting children, the any-hit one tests groups first.
// Rays as a renderer sends them on such a scene: shadow rays from the boxes and the ground
// towards points below the ceiling, camera rays from above through the ceiling, rays along
// the ground, and rays from below the ceiling upwards.
TEST(OctreeKeptGroups, SeveralGroupsPerNodeGiveTheClosestHit) {
    TableScene s(2);
    // Large slanted panes scattered across the scene, as more candidates for groups than a
    // node may hold (OctreeKept::kMaxGroups).
    MeshData panes;
    pcg32 prng(3);
    auto pu = [&] { return float(prng() >> 8) * 0x1p-24f; };
    for (int k = 0; k < 14; ++k) {
        const Point3f c(24.0f * pu() - 12.0f, 2.0f + (kCeiling - 4.0f) * pu(), 24.0f * pu() - 12.0f);
        MeshData q;
        q.positions = {c + Vector3f(-6, -0.5f, -5), c + Vector3f(6, 0.5f, -5), c + Vector3f(6, 0.8f, 5), c + Vector3f(-6, -0.2f, 5)};
        q.faces = {{0, 1, 2}, {0, 2, 3}};
        append(panes, q);
    }
    Mesh objects(s.objects, "boxes"), ground(s.ground, "ground"), ceiling(s.ceiling, "ceiling"), glass(panes, "panes");
    size_t most = 0;
    for (bool withPanes : {false, true}) {
        std::vector<const Mesh *> meshes{&objects, &ground, &ceiling};
        if (withPanes) meshes.push_back(&glass);
        auto brute = makeAccel("brute", PropertyList(), meshes);
        pcg32 rng(7);
        auto u = [&] { return float(rng() >> 8) * 0x1p-24f; };
        std::vector<Ray3f> rays;
        for (int i = 0; i < 24000; ++i) {
            Point3f origin, target;
            switch (i % 4) {
            case 0:  // from the boxes' tops and the ground towards a light below the ceiling
                origin = Point3f(24.0f * u() - 12.0f, 0.6f * u() + 1e-3f, 24.0f * u() - 12.0f);
                target = Point3f(30.0f * u() - 15.0f, kCeiling - 4.0f + 3.0f * u(), 30.0f * u() - 15.0f);
                break;
            case 1:  // from above, through the ceiling
                origin = Point3f(24.0f * u() - 12.0f, kCeiling + 5.0f + 10.0f * u(), 24.0f * u() - 12.0f);
                target = Point3f(24.0f * u() - 12.0f, 0.7f * u(), 24.0f * u() - 12.0f);
                break;
            case 2:  // along the ground
                origin = Point3f(-15.0f, 0.05f + 0.6f * u(), 24.0f * u() - 12.0f);
                target = Point3f(15.0f, 0.05f + 0.6f * u(), 24.0f * u() - 12.0f);
                break;
            default:  // from between the quads, anywhere
                origin = Point3f(24.0f * u() - 12.0f, 1.0f + (kCeiling - 2.0f) * u(), 24.0f * u() - 12.0f);
                target = Point3f(30.0f * u() - 15.0f, (kCeiling + 2.0f) * u() - 1.0f, 30.0f * u() - 15.0f);
                break;
            }
            rays.emplace_back(origin, target - origin, 0.0f, i % 3 == 0 ? 1.0f : Infinity);
        }
        for (const char *traversal : {"simd", "sorted"}) {
            auto octree = buildOctree(meshes, traversal);
            dynamic_cast<const OctreeAccel &>(*octree).forEachNode(
                [&](const OctreeAccel::NodeView &v) { most = std::max(most, v.keptGroups().size()); });
            size_t hits = 0;
            const size_t differ = differences(*octree, *brute, rays, hits);
            std::printf("[kept] panes %d, %s: at most %zu kept groups per node, kept %.0f; %zu of %zu rays hit, %zu differ\n",
                        int(withPanes), traversal, most, statsOf(*octree)["kept_refs"], hits, rays.size(), differ);
            EXPECT_GT(hits, rays.size() / 3);
            EXPECT_EQ(differ, 0u) << traversal << (withPanes ? " with the panes" : "");
        }
    }
    EXPECT_GE(most, 2u);  // the test reaches nodes with several groups
    EXPECT_LE(most, size_t(OctreeKept::kMaxGroups));
}

// A storey (an office's floor and ceiling, 60 x 40 and 3 apart, with furniture between them):
// one box around both quads is only 3 high, and the cost model, which takes rays from every
// direction and counts none that stops before a plane, prices that one group lower than two.
// But a camera ray along the storey meets the furniture or the floor or the ceiling, and the
// floor only where it crosses the floor's plane: kept triangles that lie in axis-aligned planes
// on the shell of the node's box are grouped by plane, each group in a flat box entered
// exactly where the ray meets the plane (and tested in its turn among the node's children).
// Without that rule the root kept all four triangles in one group whose box spanned the
// storey. The answers stay brute force's for closest and any hits, through the kept sets'
// one box test for all groups.
TEST(OctreeKeptGroups, AFloorAndACeilingCloseTogetherAreGroupedByPlane) {
    constexpr float kHeight = 3.0f;
    MeshData furniture;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 12; ++j)
            append(furniture, scaled(cube(3), 0.3f, Vector3f(1.5f + 3.0f * float(i), 0.3f + 0.1f * float((i + j) % 7), 1.5f + 3.2f * float(j))));
    Mesh boxes(furniture, "furniture");
    Mesh floor(quadAt(0.0f, 60.0f, 0.0f, 40.0f, 0.0f), "floor"), ceiling(quadAt(0.0f, 60.0f, 0.0f, 40.0f, kHeight), "ceiling");
    const std::vector<const Mesh *> meshes{&boxes, &floor, &ceiling};
    auto octree = buildOctree(meshes);
    size_t floorGroups = 0, ceilingGroups = 0, spanning = 0;
    dynamic_cast<const OctreeAccel &>(*octree).forEachNode([&](const OctreeAccel::NodeView &v) {
        for (const OctreeKept &g : v.keptGroups()) {
            if (g.lo[1] == 0.0f && g.hi[1] == 0.0f) ++floorGroups;
            else if (g.lo[1] == kHeight && g.hi[1] == kHeight) ++ceilingGroups;
            else if (g.lo[1] <= 0.0f && g.hi[1] >= kHeight) ++spanning;
        }
    });
    auto st = statsOf(*octree);
    std::printf("[kept] storey: %zu floor groups, %zu ceiling groups, %zu spanning both; kept %.0f in %.0f groups, %.0f sets\n",
                floorGroups, ceilingGroups, spanning, st["kept_refs"], st["kept_groups"], st["kept_sets"]);
    EXPECT_EQ(spanning, 0u);
    EXPECT_GE(floorGroups, 1u);
    EXPECT_GE(ceilingGroups, 1u);
    EXPECT_GE(st["kept_sets"], 1.0);  // a node holds both: the traversals test their boxes at once

    // Camera rays along the storey, shadow rays from the floor and the furniture upwards.
    auto brute = makeAccel("brute", PropertyList(), meshes);
    pcg32 rng(11);
    auto u = [&] { return float(rng() >> 8) * 0x1p-24f; };
    std::vector<Ray3f> rays;
    for (int i = 0; i < 20000; ++i) {
        Point3f origin, target;
        if (i % 2 == 0) {
            origin = Point3f(0.5f, 1.6f, 20.0f + u());
            target = Point3f(60.0f, kHeight * 1.4f * u() - 0.6f, 40.0f * u());
        } else {
            origin = Point3f(60.0f * u(), 0.8f * u(), 40.0f * u());
            target = Point3f(60.0f * u(), kHeight + 1.0f, 40.0f * u());
        }
        rays.emplace_back(origin, target - origin, 1e-4f, i % 3 == 0 ? 1.0f : Infinity);
    }
    size_t hits = 0;
    const size_t differ = differences(*octree, *brute, rays, hits);
    EXPECT_GT(hits, rays.size() / 2);
    EXPECT_EQ(differ, 0u);
}

// A large slanted triangle through a sparse scene: eight small cubes at the centres of the
// octants of [0, 8]^3 and one triangle on the plane x + y + z = 12, which passes between them
// and crosses six of the octants. Sent down, it would stretch each of those children's boxes
// from its cube (0.3 across) to most of the child's cell, and every ray entering one would
// test the cube's triangles. Kept at the root, it costs one list in a box as large as the
// root's. The kept-triangle search must price the stretched boxes: before it did
// (bench/README.md, forty-third round), it priced only the triangle's own copies, which cost
// less than a list tested by every ray, and sent the triangle down.
TEST(OctreeKeptGroups, ATriangleThatWouldStretchItsChildrensBoxesIsKept) {
    MeshData cubes;
    for (int c = 0; c < 8; ++c)
        append(cubes, scaled(cube(1), 0.15f, Vector3f(c & 1 ? 6.0f : 2.0f, c & 2 ? 6.0f : 2.0f, c & 4 ? 6.0f : 2.0f)));
    MeshData slanted;
    slanted.positions = {Point3f(8.0f, 4.0f, 0.0f), Point3f(0.0f, 8.0f, 4.0f), Point3f(4.0f, 0.0f, 8.0f)};
    slanted.faces = {{0, 1, 2}};
    Mesh small(cubes, "cubes"), large(slanted, "slanted");
    const std::vector<const Mesh *> meshes{&small, &large};
    auto octree = buildOctree(meshes);
    std::vector<OctreeKept> root;
    uint32_t rootKept = 0;
    dynamic_cast<const OctreeAccel &>(*octree).forEachNode([&](const OctreeAccel::NodeView &v) {
        if (v.depth != 0) return;
        root = v.keptGroups();
        rootKept = v.ref & OctreeNode::kKeptMask;
    });
    std::printf("[kept] slanted triangle over %zu cube triangles: the root keeps %u in %zu groups\n",
                cubes.faces.size(), rootKept, root.size());
    ASSERT_EQ(rootKept, 1u);
    ASSERT_EQ(root.size(), 1u);
    for (int a = 0; a < 3; ++a) {  // the slanted triangle's own box
        EXPECT_EQ(root[0].lo[a], 0.0f);
        EXPECT_EQ(root[0].hi[a], 8.0f);
    }
    // And the answers stay brute force's, for rays from everywhere through the scene.
    auto brute = makeAccel("brute", PropertyList(), meshes);
    pcg32 rng(11);
    auto u = [&] { return float(rng() >> 8) * 0x1p-24f; };
    std::vector<Ray3f> rays;
    for (int i = 0; i < 6000; ++i) {
        const Point3f origin(12.0f * u() - 2.0f, 12.0f * u() - 2.0f, 12.0f * u() - 2.0f);
        const Point3f target(1.0f + 6.0f * u(), 1.0f + 6.0f * u(), 1.0f + 6.0f * u());
        rays.emplace_back(origin, target - origin, 0.0f, i % 3 == 0 ? 1.0f : Infinity);
    }
    size_t hits = 0;
    EXPECT_EQ(differences(*octree, *brute, rays, hits), 0u);
    EXPECT_GT(hits, rays.size() / 4);
}
