/// \file test_area.cpp
/// \brief The discrete distribution, uniform sampling of meshes by area and the area light:
/// frequencies and moments against exact values, one-sided emission by the shading normal, the
/// density of sample() against pdf(), and irradiance from a polygon against Lambert's formula.
#include <gtest/gtest.h>
#include <nori/emitter.h>
#include <nori/mesh.h>
#include <pcg_random.hpp>
#include <cmath>

using namespace nori;

namespace {

float uniform(pcg32 &rng) { return float(rng() >> 8) * 0x1p-24f; }

/// A mesh from positions and faces (and optional per-vertex normals), carrying an area light of
/// radiance \p radiance, activated like a parsed one.
std::unique_ptr<Mesh> emitterMesh(std::vector<Point3f> positions, std::vector<std::array<uint32_t, 3>> faces,
                                  std::vector<Normal3f> normals = {}, float radiance = 1.0f) {
    MeshData data;
    data.positions = std::move(positions);
    data.faces = std::move(faces);
    data.normals = std::move(normals);
    auto mesh = std::make_unique<Mesh>(std::move(data), "test");
    PropertyList props;
    props.setLocation("test");
    props.setColor("radiance", Color3f(radiance), "test");
    mesh->addChild(NoriObjectFactory::createInstance(NoriObject::EEmitter, "area", props));
    mesh->activate();
    return mesh;
}

TEST(DiscretePDF, ProbabilitiesAndInversion) {
    DiscretePDF d;
    for (float w : {1.0f, 0.0f, 3.0f, 4.0f}) d.append(w);
    EXPECT_FLOAT_EQ(d.normalize(), 8.0f);
    ASSERT_EQ(d.size(), 4u);
    EXPECT_FLOAT_EQ(d[0], 0.125f);
    EXPECT_FLOAT_EQ(d[1], 0.0f);
    EXPECT_FLOAT_EQ(d[2], 0.375f);
    EXPECT_FLOAT_EQ(d[3], 0.5f);
    EXPECT_EQ(d.sample(0.0f), 0u);
    EXPECT_EQ(d.sample(0.1249f), 0u);
    EXPECT_EQ(d.sample(0.125f), 2u);  // the empty entry is never chosen
    EXPECT_EQ(d.sample(0.4999f), 2u);
    EXPECT_EQ(d.sample(0.5f), 3u);
    EXPECT_EQ(d.sample(0.99999994f), 3u);
    float u = 0.3125f;  // halfway through entry 2
    EXPECT_EQ(d.sampleReuse(u), 2u);
    EXPECT_FLOAT_EQ(u, 0.5f);
    u = 0.99999994f;
    EXPECT_EQ(d.sampleReuse(u), 3u);
    EXPECT_LT(u, 1.0f);
}

TEST(DiscretePDF, EmptyDistributionNormalizesToZero) {
    DiscretePDF d;
    d.append(0.0f);
    EXPECT_EQ(d.normalize(), 0.0f);
}

// Two triangles of areas 0.5 and 1.5 (a trapezoid in the z = 0 plane): a point falls on the
// second with probability 3/4, and the mean of the points is the trapezoid's centroid.
TEST(MeshSampling, UniformByArea) {
    auto mesh = emitterMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {3, 1, 0}}, {{0, 1, 2}, {1, 3, 2}});
    EXPECT_FLOAT_EQ(mesh->surfaceArea(), 2.0f);
    pcg32 rng(1);
    const int n = 400000;
    int second = 0;
    Vector3d mean = Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
        MeshSample s;
        mesh->samplePosition(Point2f(uniform(rng), uniform(rng)), s);
        ASSERT_FLOAT_EQ(s.pdf, 0.5f);
        ASSERT_NEAR(s.p.z(), 0.0f, 0.0f);
        second += s.p.x() + s.p.y() > 1.0f;  // beyond the shared edge (1,0,0)-(0,1,0)
        mean += s.p.cast<double>();
    }
    EXPECT_NEAR(double(second) / n, 0.75, 5.0 * std::sqrt(0.75 * 0.25 / n));
    mean /= double(n);
    // Centroid: (0.5 * c1 + 1.5 * c2) / 2 with c1 = (1/3, 1/3), c2 = (4/3, 2/3).
    Vector3d centroid(0.25 * (1.0 / 3.0) + 0.75 * (4.0 / 3.0), 0.25 * (1.0 / 3.0) + 0.75 * (2.0 / 3.0), 0.0);
    // Standard deviation of x over the trapezoid is below 1: 5 sigma of the mean is < 5 / sqrt(n).
    EXPECT_NEAR(mean.x(), centroid.x(), 5.0 / std::sqrt(double(n)));
    EXPECT_NEAR(mean.y(), centroid.y(), 5.0 / std::sqrt(double(n)));
}

} // namespace

namespace {

// furnace.obj's convention: winding normal one way, vertex normals the other. The light emits on
// the side of the shading normal, and sample() returns radiance / pdf with pdf() agreeing.
TEST(AreaLight, EmitsOnTheShadingNormalSide) {
    // A unit square in z = 0 wound towards +z, with vertex normals pointing to -z.
    std::vector<Normal3f> down(4, Normal3f(0, 0, -1));
    auto mesh = emitterMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}, down, 2.0f);
    const Emitter &light = *mesh->emitter();
    pcg32 rng(2);
    for (float side : {-1.0f, 1.0f}) {
        EmitterQueryRecord rec(Point3f(0.5f, 0.5f, 2.0f * side));
        Color3f value = light.sample(rec, Point2f(uniform(rng), uniform(rng)));
        ASSERT_GT(rec.pdf, 0.0f);
        EXPECT_NEAR(light.pdf(rec), rec.pdf, 1e-5f * rec.pdf);
        // pdf = distance^2 / (|cos| * area)
        float cosine = std::abs(rec.wi.z());
        EXPECT_NEAR(rec.pdf, rec.distance * rec.distance / cosine, 1e-4f * rec.pdf);
        if (side < 0.0f) {
            EXPECT_TRUE((light.eval(rec) == Color3f(2.0f)).all());  // below: facing the shading normal
            EXPECT_NEAR(value[0], 2.0f / rec.pdf, 1e-5f * value[0]);
        } else {
            EXPECT_TRUE(light.eval(rec).isZero());  // above: the winding side, dark
            EXPECT_TRUE(value.isZero());
        }
    }
}

/// Irradiance at the origin (normal +z) from a uniform Lambertian polygon of radiance 1:
/// Lambert's formula E = 1/2 sum_i Theta_i (n . g_i), Theta_i the angle the edge (v_i, v_i+1)
/// subtends and g_i the unit normal of the plane through the origin and that edge.
double lambertIrradiance(const std::vector<Vector3d> &v) {
    double sum = 0.0;
    for (size_t i = 0; i < v.size(); ++i) {
        Vector3d a = v[i].normalized(), b = v[(i + 1) % v.size()].normalized();
        double theta = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
        sum += theta * a.cross(b).normalized().z();
    }
    return 0.5 * std::abs(sum);
}

TEST(AreaLight, SampledIrradianceMatchesLambert) {
    // A tilted quad above the origin, wound so that its normal faces the origin.
    std::vector<Point3f> quad = {{-0.3f, 0.2f, 1.0f}, {0.9f, 0.1f, 1.4f}, {1.1f, 1.3f, 1.2f}, {-0.2f, 1.0f, 0.8f}};
    Vector3f ng = (quad[1] - quad[0]).cross(quad[2] - quad[0]);
    if (ng.dot(quad[0]) > 0.0f) std::reverse(quad.begin(), quad.end());
    auto mesh = emitterMesh(quad, {{0, 1, 2}, {0, 2, 3}});
    std::vector<Vector3d> corners;
    for (const Point3f &p : quad) corners.push_back(p.cast<double>());
    const double reference = lambertIrradiance(corners);
    pcg32 rng(3);
    const int n = 200000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
        EmitterQueryRecord rec(Point3f(0, 0, 0));
        Color3f value = mesh->emitter()->sample(rec, Point2f(uniform(rng), uniform(rng)));
        double e = value[0] * std::max(0.0f, rec.wi.z());
        sum += e;
        sum2 += e * e;
    }
    double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
    std::printf("irradiance from a quad: %.5f (sigma %.1e), Lambert %.5f\n", mean, sigma, reference);
    EXPECT_NEAR(mean, reference, 5.0 * sigma);
    EXPECT_GT(reference, 0.1);
}

TEST(AreaLight, MeshesWithoutAnEmitterKeepNoDistribution) {
    MeshData data;
    data.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    data.faces = {{0, 1, 2}};
    Mesh mesh(std::move(data), "plain");
    mesh.activate();
    EXPECT_FALSE(mesh.isEmitter());
    EXPECT_EQ(mesh.surfaceArea(), 0.0f);
}

} // namespace
