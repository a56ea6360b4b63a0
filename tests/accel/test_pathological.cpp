/// \file test_pathological.cpp
/// \brief Pathological inputs for the octree: each must build with a bounded number of triangle
/// references and bytes (never a bound on time) and answer exactly like brute force.
#include "robust_util.h"
#include "test_geometry.h"

#include <nori/objloader.h>
#include <nori/parser.h>
#include <nori/scene.h>
#include <ray_sets.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <pcg_random.hpp>

using namespace nori;
using namespace nori::robust;
namespace fs = std::filesystem;

namespace {

float uniform01(pcg32 &rng) { return float(rng() >> 8) * 0x1p-24f; }

/// \p n triangles sharing the apex (0, 0, 0), their far edges on the circle of radius 1 at z = 1.
MeshData fan(uint32_t n) {
    MeshData m;
    m.positions.emplace_back(0.0f, 0.0f, 0.0f);
    for (uint32_t i = 0; i < n; ++i) {
        float a = 2.0f * Pi * float(i) / float(n);
        m.positions.emplace_back(std::cos(a), std::sin(a), 1.0f);
    }
    for (uint32_t i = 0; i < n; ++i) m.faces.push_back({0, 1 + i, 1 + (i + 1) % n});
    return m;
}

/// \p n copies of one triangle (each with its own vertices, at identical positions).
MeshData identical(uint32_t n) {
    MeshData m;
    for (uint32_t i = 0; i < n; ++i) {
        m.positions.insert(m.positions.end(), {Point3f(-0.3f, -0.2f, 0.1f), Point3f(0.4f, -0.1f, 0.2f), Point3f(0.0f, 0.5f, -0.1f)});
        m.faces.push_back({3 * i, 3 * i + 1, 3 * i + 2});
    }
    return m;
}

/// \p n long thin triangles, each from one face of the box [-1, 1]^3 to the opposite one.
MeshData needles(uint32_t n) {
    MeshData m;
    pcg32 rng(11);
    auto u = [&] { return uniform01(rng) * 2.0f - 1.0f; };
    for (uint32_t i = 0; i < n; ++i) {
        int axis = int(i % 3);
        Point3f a(u(), u(), u()), b(u(), u(), u());
        a[axis] = -1.0f;
        b[axis] = 1.0f;
        Vector3f w = Vector3f::Zero();
        w[(axis + 1) % 3] = 1e-3f;  // width
        uint32_t base = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {a, Point3f(a + w), b});
        m.faces.push_back({base, base + 1, base + 2});
    }
    return m;
}

/// A ~100k-triangle torus of size ~1 standing on two huge ground triangles 10^4 wide.
std::vector<MeshData> teapotInAStadium() {
    MeshData object = torus(0.7f, 0.25f, 250, 200);
    MeshData ground;
    ground.positions = {Point3f(-1e4f, -0.25f, -1e4f), Point3f(1e4f, -0.25f, -1e4f), Point3f(1e4f, -0.25f, 1e4f),
                        Point3f(-1e4f, -0.25f, 1e4f)};
    ground.faces = {{0, 1, 2}, {0, 2, 3}};
    return {object, ground};
}

/// Zero-area, collinear and repeated-index triangles only.
MeshData degenerate(uint32_t n) {
    MeshData m;
    pcg32 rng(5);
    auto u = [&] { return uniform01(rng) * 2.0f - 1.0f; };
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t base = uint32_t(m.positions.size());
        Point3f a(u(), u(), u()), b(u(), u(), u());
        switch (i % 3) {
        case 0:  // all three corners at one point
            m.positions.insert(m.positions.end(), {a, a, a});
            m.faces.push_back({base, base + 1, base + 2});
            break;
        case 1:  // collinear: the third corner between the other two
            m.positions.insert(m.positions.end(), {a, b, Point3f(0.5f * (a + b))});
            m.faces.push_back({base, base + 1, base + 2});
            break;
        default:  // a repeated index
            m.positions.insert(m.positions.end(), {a, b});
            m.faces.push_back({base, base + 1, base + 1});
            break;
        }
    }
    return m;
}

MeshData oneTriangle() {
    MeshData m;
    m.positions = {Point3f(-1, -1, 0), Point3f(1, -1, 0.2f), Point3f(0, 1, -0.1f)};
    m.faces = {{0, 1, 2}};
    return m;
}

struct Pathology {
    std::string name;
    std::vector<MeshData> meshes;
    /// Bound on triangle references per triangle beyond the build rule's own budget (see
    /// octreeSettings()): inputs no split can separate (copies of one triangle) get 1.
    double maxRefsPerTriangle;
};

/// Octree settings each pathology is built with, and the references per triangle each rule
/// promises: the defaults (`sah`: at most 1.5), its deep small-leaf variant, and the other rules
/// with the seed report's deep tree of small leaves, where duplication blows up first (at most 8).
struct Setting {
    std::string name;
    PropertyList props;
    double maxRefsPerTriangle;
};
std::vector<Setting> octreeSettings(const PropertyList &base) {
    std::vector<Setting> settings{{"default", base, 1.5}};
    for (const char *rule : {"sah", "count", "seed"}) {
        PropertyList deep = base;
        deep.setString("buildRule", rule);
        deep.setInteger("leafSize", rule == std::string("sah") ? 1 : 10);
        deep.setInteger("maxDepth", 30);
        settings.push_back({std::string(rule) + " leaf " + (rule == std::string("sah") ? "1" : "10") + " depth 30", deep,
                            rule == std::string("sah") ? 1.5 : 8.0});
    }
    return settings;
}

/// Rays through the scene's box (or [-1, 1]^3 if it is empty), plus rays aimed at vertices.
std::vector<Ray3f> probeRays(const std::vector<const Mesh *> &meshes, size_t count) {
    BoundingBox3f box;
    for (const Mesh *m : meshes)
        if (m->triangleCount()) box.expandBy(m->bbox());
    // The stadium's box is huge: aim at the object's scale instead, where the triangles are.
    if (!box.isValid() || box.extents().maxCoeff() > 100.0f) box = BoundingBox3f(Point3f(-1, -1, -1), Point3f(1, 1, 1));
    std::vector<Ray3f> rays = randomBoxRays(box, count, 99);
    pcg32 rng(17);
    for (const Mesh *m : meshes)
        for (uint32_t i = 0; i < std::min<uint32_t>(m->vertexCount(), 300); ++i) {
            const Point3f &target = m->positions()[rng.operator()(m->vertexCount())];
            Point3f origin = box.center() + 2.0f * box.extents().maxCoeff() *
                                                   Vector3f(uniform01(rng) - 0.5f, uniform01(rng) - 0.5f, 1.0f);
            rays.emplace_back(origin, target - origin);
        }
    return rays;
}

/// Does \p ray cross the triangle of \p hit at least 2^-17 of the problem's scale inside its
/// boundary (a hit every correct intersector and every octree must find)?
bool robustHit(const Ray3f &ray, const Hit &hit, const std::vector<const Mesh *> &meshes) {
    uint32_t f = hit.prim;
    size_t m = 0;
    while (f >= meshes[m]->triangleCount()) f -= meshes[m++]->triangleCount();
    V3d p0 = meshes[m]->vertex(f, 0).cast<double>(), p1 = meshes[m]->vertex(f, 1).cast<double>(),
        p2 = meshes[m]->vertex(f, 2).cast<double>();
    V3d o = ray.o.cast<double>(), d = ray.d.cast<double>();
    double size = std::max({(p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()}) / d.norm();
    double t0 = std::max(double(ray.mint), hit.t - 2 * size), t1 = std::min(double(ray.maxt), hit.t + 2 * size);
    double scale = std::max({o.cwiseAbs().maxCoeff(), (o + hit.t * d).cwiseAbs().maxCoeff(), hit.t * d.norm()});
    return crossesInterior(o + t0 * d, o + t1 * d, p0, p1, p2, 0x1p-17 * scale);
}

void checkPathology(const Pathology &p) {
    std::vector<std::unique_ptr<Mesh>> owned;
    std::vector<const Mesh *> meshes;
    size_t triangles = 0;
    for (const MeshData &data : p.meshes) {
        owned.push_back(std::make_unique<Mesh>(data, p.name));
        meshes.push_back(owned.back().get());
        triangles += data.faces.size();
    }
    // Same intersector on both sides where the accels support choosing it.
    PropertyList props = intersectorProps("mt");
    std::unique_ptr<Accel> brute = makeAccel("brute", props, meshes);
    if (!brute) {
        props = intersectorProps("");
        brute = makeAccel("brute", props, meshes);
    }
    ASSERT_TRUE(brute);
    if (!octreeAvailable()) GTEST_SKIP() << "the octree accel is not in this build";
    for (const Setting &setting : octreeSettings(props)) {
    const std::string &settingsName = setting.name;
    SCOPED_TRACE(settingsName);
    std::unique_ptr<Accel> octree = makeAccel("octree", setting.props, meshes);
    ASSERT_TRUE(octree);

    // Build figures (for the table) and the bounds that catch a blow-up.
    double refs = stat(*octree, "triangle_refs").value_or(-1), bytes = stat(*octree, "bytes").value_or(-1);
    double depth = stat(*octree, "max_depth_reached").value_or(-1), leaves = stat(*octree, "leaf_nodes").value_or(-1);
    double refsPerTri = triangles ? refs / double(triangles) : 0.0;
    std::printf("[ patho    ] %-22s %-22s triangles %7zu  refs/tri %8.3f  bytes %11.0f  depth %3.0f  leaves %8.0f\n",
                p.name.c_str(), settingsName.c_str(), triangles, refsPerTri, bytes, depth, leaves);
    ASSERT_GE(refs, 0.0) << "octree reports no triangle_refs";
    ASSERT_GE(bytes, 0.0) << "octree reports no bytes";
    // `seed` has no no-progress test (the seed report's rule ends only at maxDepth and the
    // budget), so only its budget bounds it; the other rules stop splitting what no split separates.
    const bool seedRule = setting.props.getString("buildRule", "sah") == "seed";
    EXPECT_LE(refsPerTri, seedRule ? setting.maxRefsPerTriangle : std::min(p.maxRefsPerTriangle, setting.maxRefsPerTriangle))
        << p.name;
    // Memory proportional to the references (no hidden growth of empty nodes): 128 bytes per
    // reference covers a reference, its share of a leaf and of the inner nodes above it.
    EXPECT_LE(bytes, 128.0 * refs + 65536.0) << p.name;

    size_t mismatches = 0;
    for (const Ray3f &ray : probeRays(meshes, 2500)) {
        Hit a, b;
        bool ha = brute->intersect(ray, a), hb = octree->intersect(ray, b);
        bool ok = ha == hb && octree->occluded(ray) == ha;
        // Ties (identical or touching triangles) may pick another triangle at the same t.
        if (ok && ha) ok = std::abs(a.t - b.t) <= 1e-6f * std::max(1.0f, std::abs(a.t));
        // Moeller-Trumbore invents hits on slivers (the fan's) just outside the triangle, hence
        // outside every cell the exact overlap test gives it: an octree rightly never finds them.
        if (!ok && ha && (!hb || a.t < b.t) && !robustHit(ray, a, meshes)) ok = true;
        if (!ok && ++mismatches <= 5)
            ADD_FAILURE() << p.name << ": o=" << ray.o.transpose() << " d=" << ray.d.transpose() << " brute "
                          << (ha ? "hit" : "miss") << " t=" << a.t << ", octree " << (hb ? "hit" : "miss")
                          << " t=" << b.t;
    }
    EXPECT_EQ(mismatches, 0u) << p.name;
    }
}

TEST(Pathological, FanOf100kTrianglesSharingOneVertex) { checkPathology({"fan 100k", {fan(100000)}, 8}); }
TEST(Pathological, TenThousandIdenticalTriangles) { checkPathology({"identical 10k", {identical(10000)}, 1}); }
TEST(Pathological, TenThousandNeedlesSpanningTheBox) { checkPathology({"needles 10k", {needles(10000)}, 8}); }
TEST(Pathological, TeapotInAStadium) { checkPathology({"teapot in stadium", teapotInAStadium(), 8}); }
TEST(Pathological, AllDegenerateTriangles) { checkPathology({"degenerate 3k", {degenerate(3000)}, 8}); }
TEST(Pathological, EmptyScene) { checkPathology({"empty", {}, 0}); }
TEST(Pathological, EmptyMesh) { checkPathology({"empty mesh", {MeshData()}, 0}); }
TEST(Pathological, OneTriangle) { checkPathology({"one triangle", {oneTriangle()}, 8}); }

// A 40k-triangle torus 1e-3 across on a ground 2e6 wide (a ratio of 2e9, beyond the reach of
// maxDepth 24 in halvings): the levels of empty space above it must not use up the depth, or
// the torus ends as one leaf of all its triangles. Its subtree must split it like any object,
// and answer as brute force does on rays aimed at its vertices.
TEST(Pathological, SpeckOnAContinentIsSubdividedLikeAnyObject) {
    if (!octreeAvailable()) GTEST_SKIP() << "the octree accel is not in this build";
    MeshData speck = torus(0.7f, 0.25f, 200, 100);
    for (Point3f &p : speck.positions) p *= 1e-3f;
    MeshData ground;
    ground.positions = {Point3f(-1e6f, -0.3e-3f, -1e6f), Point3f(1e6f, -0.3e-3f, -1e6f), Point3f(1e6f, -0.3e-3f, 1e6f),
                        Point3f(-1e6f, -0.3e-3f, 1e6f)};
    ground.faces = {{0, 1, 2}, {0, 2, 3}};
    Mesh a(speck, "speck"), b(ground, "continent");
    std::vector<const Mesh *> meshes = {&a, &b};
    std::unique_ptr<Accel> octree = makeAccel("octree", intersectorProps(""), meshes);
    std::unique_ptr<Accel> brute = makeAccel("brute", intersectorProps(""), meshes);
    ASSERT_TRUE(octree && brute);
    const double perLeaf = stat(*octree, "avg_tris_per_leaf").value_or(1e9);
    std::printf("[ speck    ] %.1f triangles per leaf, depth %.0f\n", perLeaf,
                stat(*octree, "max_depth_reached").value_or(-1));
    EXPECT_LE(perLeaf, 64.0);
    pcg32 rng(23);
    size_t hits = 0;
    for (int i = 0; i < 3000; ++i) {
        const Point3f target = speck.positions[rng(uint32_t(speck.positions.size()))];
        const Point3f origin(2e-3f * (uniform01(rng) - 0.5f), 1e-3f * uniform01(rng) + 0.5e-3f, 2e-3f * (uniform01(rng) - 0.5f));
        const Ray3f ray(origin, target - origin);
        Hit h1, h2;
        const bool b1 = brute->intersect(ray, h1), b2 = octree->intersect(ray, h2);
        ASSERT_EQ(b1, b2) << "o=" << origin.transpose() << " d=" << ray.d.transpose();
        if (b1) {
            ASSERT_EQ(h1.t, h2.t) << "o=" << origin.transpose() << " d=" << ray.d.transpose();
        }
        hits += b1;
    }
    EXPECT_GT(hits, 1500u);
}

// Corners past +-1.7e38 make the scene's sides longer than the largest float: the octree's
// cells and their midpoints would be infinite and NaN (it then missed every triangle but the
// ground). Refused with a message naming the mesh, by every accelerator alike.
TEST(Pathological, ASceneBeyondTheFloatRangeIsRefusedClearly) {
    MeshData ground;
    ground.positions = {Point3f(-3e38f, 0, -3e38f), Point3f(3e38f, 0, -3e38f), Point3f(3e38f, 0, 3e38f)};
    ground.faces = {{0, 1, 2}};
    Mesh mesh(ground, "continent.obj");
    std::vector<const Mesh *> meshes = {&mesh};
    for (const char *type : {"brute", "octree"}) {
        if (std::string(type) == "octree" && !octreeAvailable()) continue;
        try {
            makeAccel(type, intersectorProps(""), meshes);
            ADD_FAILURE() << type << " accepted a scene wider than the float range";
        } catch (const NoriException &e) {
            EXPECT_NE(std::string(e.what()).find("float range"), std::string::npos) << e.what();
        }
    }
    // Up to 1e38 (sides of 2e38) the same scene is accepted.
    for (Point3f &p : ground.positions) p /= 3.0f;
    Mesh smaller(ground, "continent.obj");
    EXPECT_TRUE(makeAccel("brute", intersectorProps(""), {&smaller}));
}

// Degenerate triangles are valid input: the OBJ loader keeps them, queries stay sane, and a
// triangle whose corners coincide is never hit (its edges are exactly zero). The octree leaves
// out those whose corners lie exactly on one line (the points and the repeated indices of
// degenerate(): two thirds), which no ray can hit: every ray that reached a point-like triangle
// would otherwise take the kernel's exact-arithmetic path.
TEST(Pathological, DegenerateTrianglesLoadAndQuerySafely) {
    MeshData parsed = parseObj("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 1 2\nf 1 2 3\nf 2 2 2\n", "degenerate.obj");
    EXPECT_EQ(parsed.faces.size(), 3u);

    Mesh mesh(degenerate(3000), "degenerate");
    std::vector<const Mesh *> list = {&mesh};
    std::vector<std::string> types = {"brute"};
    if (octreeAvailable()) types.push_back("octree");
    for (const std::string &type : types) {
        std::unique_ptr<Accel> accel = makeAccel(type, intersectorProps(""), list);
        ASSERT_TRUE(accel);
        if (type == "octree") {
            EXPECT_LE(stat(*accel, "triangle_refs").value_or(1e9), 1000.0);
        }
        size_t hits = 0;
        for (const Ray3f &ray : probeRays(list, 2000)) {
            Hit hit;
            if (!accel->intersect(ray, hit)) continue;
            ++hits;
            EXPECT_TRUE(std::isfinite(hit.t) && hit.t >= ray.mint && hit.t <= ray.maxt) << type;
            EXPECT_NE(hit.prim % 3, 0u) << type << ": a point-like triangle was hit";
            Intersection its;
            accel->completeIntersection(ray, hit, its);
            EXPECT_TRUE(its.p.allFinite() && its.geoFrame.n.allFinite()) << type;
        }
        std::printf("[ degen    ] %-6s %zu hits on near-degenerate (collinear in float) triangles\n", type.c_str(), hits);
    }
}

// A camera inside a closed mesh: with the watertight intersector every pixel sees the mesh.
TEST(Pathological, CameraInsideAClosedMeshSeesNoBackground) {
    char pattern[] = "/tmp/nori-inside-XXXXXX";
    ASSERT_TRUE(mkdtemp(pattern));
    fs::path dir = pattern;
    {
        MeshData sphere = icosphere(4);
        std::ofstream obj(dir / "sphere.obj");
        obj.precision(9);
        for (const Point3f &p : sphere.positions) obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
        for (const auto &f : sphere.faces) obj << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
        std::ofstream xml(dir / "inside.xml");
        // Off-centre camera, wide angle: rays cross the sphere's triangles at many angles.
        xml << "<scene><integrator type=\"normals\"/>\n"
               "<camera type=\"perspective\"><transform name=\"toWorld\">"
               "<lookat origin=\"0.1,0.05,-0.2\" target=\"0.3,0.2,1\" up=\"0,1,0\"/></transform>"
               "<float name=\"fov\" value=\"120\"/><integer name=\"width\" value=\"96\"/>"
               "<integer name=\"height\" value=\"96\"/></camera>\n"
               "<mesh type=\"obj\"><string name=\"filename\" value=\"sphere.obj\"/></mesh></scene>\n";
    }
    size_t watertightRuns = 0;
    // The octree is the subject; brute force stands in only where there is no octree.
    std::vector<std::string> accels = {octreeAvailable() ? "octree" : "brute"};
    for (const std::string &accel : accels)
        for (std::string isect : {"mt", "watertight"}) {
            SceneOverrides overrides;
            overrides.accelType = accel;
            overrides.accelProps.setString("intersector", isect, "test");
            std::unique_ptr<Scene> scene;
            try {
                scene = loadScene((dir / "inside.xml").string(), overrides);
            } catch (const NoriException &e) {
                // "unused property 'intersector'": this accel cannot choose its intersector yet.
                if (std::string(e.what()).find("intersector") != std::string::npos) continue;
                throw;
            }
            pcg32 rng(23);
            size_t background = 0, rays = 0;
            const Vector2i size = scene->camera().outputSize();
            for (int y = 0; y < size.y(); ++y)
                for (int x = 0; x < size.x(); ++x)
                    for (int s = 0; s < 8; ++s) {
                        Ray3f ray;
                        scene->camera().sampleRay(ray, Point2f(x + uniform01(rng), y + uniform01(rng)), Point2f(0.5f, 0.5f));
                        Intersection its;
                        ++rays;
                        background += !scene->rayIntersect(ray, its);
                    }
            std::printf("[ inside   ] %-6s %-10s %zu of %zu camera rays see the background\n", accel.c_str(),
                        isect.c_str(), background, rays);
            if (isect == "watertight") {
                ++watertightRuns;
                EXPECT_EQ(background, 0u) << accel;
            }
        }
    std::error_code ec;
    fs::remove_all(dir, ec);
    if (watertightRuns == 0) GTEST_SKIP() << "no accel supports intersector=watertight yet";
}

} // namespace
