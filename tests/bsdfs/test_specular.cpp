/// \file test_specular.cpp
/// \brief The Dirac BSDFs: mirror and dielectric (directions, weights, eta, energy).
#include "bsdf_util.h"
#include <error_of.h>
#include <gtest/gtest.h>
#include <nori/fresnel.h>

using namespace nori;
using namespace nori::test;

TEST(Mirror, ReflectsWithWeightOne) {
    auto mirror = makeBSDF("mirror");
    EXPECT_FALSE(mirror->isDiffuse());
    Vector3f wi = direction(37.0f, 120.0f);
    BSDFQueryRecord rec(wi);
    Color3f w = mirror->sample(rec, Point2f(0.3f, 0.8f));
    EXPECT_TRUE((w == Color3f(1.0f)).all());
    EXPECT_EQ(rec.measure, EMeasure::Discrete);
    EXPECT_EQ(rec.eta, 1.0f);
    EXPECT_NEAR((rec.wo - Vector3f(-wi.x(), -wi.y(), wi.z())).norm(), 0.0f, 1e-7f);
    // Dirac: no density, no value for any pair.
    EXPECT_EQ(mirror->pdf(BSDFQueryRecord(wi, rec.wo, EMeasure::Discrete)), 0.0f);
    EXPECT_TRUE((mirror->eval(BSDFQueryRecord(wi, rec.wo, EMeasure::SolidAngle)) == 0.0f).all());
}

TEST(Mirror, BackSideIsBlack) {
    auto mirror = makeBSDF("mirror");
    BSDFQueryRecord rec(direction(120.0f));
    EXPECT_TRUE((mirror->sample(rec, Point2f(0.5f, 0.5f)) == 0.0f).all());
}

TEST(Dielectric, NoriDefaultsAreBK7AndAir) {
    EXPECT_EQ(makeBSDF("dielectric")->toString(), "Dielectric[intIOR=1.5046, extIOR=1.000277]");
}

TEST(Dielectric, RejectsNonPositiveIndices) {
    for (const char *name : {"intIOR", "extIOR"})
        for (float value : {0.0f, -1.5f}) {
            PropertyList props;
            props.setFloat(name, value, "glass.xml:7");
            std::string message = errorOf([&] { makeBSDF("dielectric", props); });
            EXPECT_NE(message.find("glass.xml:7: "), std::string::npos) << message;
            EXPECT_NE(message.find(std::string(name) + " must be positive"), std::string::npos) << message;
        }
}

namespace {
std::unique_ptr<BSDF> glass(float intIOR, float extIOR) {
    PropertyList props;
    props.setFloat("intIOR", intIOR);
    props.setFloat("extIOR", extIOR);
    return makeBSDF("dielectric", props);
}
} // namespace

TEST(Dielectric, ReflectsWithFresnelProbability) {
    auto bsdf = glass(1.5f, 1.0f);
    for (float deg : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f}) {
        Vector3f wi = direction(deg, 30.0f);
        float F = fresnelDielectric(wi.z(), 1.0f, 1.5f);
        // The first sample dimension decides: reflection exactly below F.
        BSDFQueryRecord below(wi), above(wi);
        bsdf->sample(below, Point2f(F * 0.999f, 0.5f));
        bsdf->sample(above, Point2f(std::min(F * 1.001f + 1e-6f, 0.999999f), 0.5f));
        EXPECT_GT(below.wo.z(), 0.0f) << deg;
        EXPECT_LT(above.wo.z(), 0.0f) << deg;
        // And over many samples, the reflected fraction matches F (5 binomial sigmas).
        Uniform u(7);
        const int n = 200000;
        int reflected = 0;
        for (int i = 0; i < n; ++i) {
            BSDFQueryRecord rec(wi);
            bsdf->sample(rec, u.next2D());
            reflected += rec.wo.z() > 0.0f;
        }
        EXPECT_NEAR(double(reflected) / n, F, 5.0 * std::sqrt(F * (1.0 - F) / n) + 1e-9) << deg;
    }
}

TEST(Dielectric, RefractionWeightIsTheRadianceScalingAndEtaUndoesIt) {
    auto bsdf = glass(1.5f, 1.0f);
    for (float deg : {0.0f, 25.0f, 70.0f}) {
        // Entering the glass from air.
        BSDFQueryRecord in(direction(deg, 200.0f));
        Color3f w = bsdf->sample(in, Point2f(0.999f, 0.5f));
        ASSERT_LT(in.wo.z(), 0.0f);
        EXPECT_EQ(in.measure, EMeasure::Discrete);
        EXPECT_FLOAT_EQ(in.eta, 1.5f);
        EXPECT_NEAR(w[0], 1.0f / (1.5f * 1.5f), 1e-6f);
        EXPECT_NEAR(w[0] * in.eta * in.eta, 1.0f, 1e-6f);  // what Russian roulette sees
        EXPECT_NEAR(std::sin(degToRad(deg)), 1.5f * std::sqrt(1.0f - in.wo.z() * in.wo.z()), 1e-5f);
        // The reversed path: from inside along wo, back out to wi; the factors cancel.
        BSDFQueryRecord out(in.wo);
        Color3f w2 = bsdf->sample(out, Point2f(0.999f, 0.5f));
        ASSERT_GT(out.wo.z(), 0.0f);
        EXPECT_NEAR((out.wo - in.wi).norm(), 0.0f, 1e-5f);
        EXPECT_FLOAT_EQ(out.eta, 1.0f / 1.5f);
        EXPECT_NEAR(w[0] * w2[0], 1.0f, 1e-5f);
        EXPECT_NEAR(in.eta * out.eta, 1.0f, 1e-6f);
    }
}

TEST(Dielectric, TotalInternalReflectionInside) {
    auto bsdf = glass(1.5f, 1.0f);
    // 60 degrees inside glass is beyond the critical angle: always reflected, weight 1.
    for (float u : {0.0f, 0.5f, 0.999f}) {
        BSDFQueryRecord rec(direction(120.0f, 10.0f));
        Color3f w = bsdf->sample(rec, Point2f(u, 0.3f));
        EXPECT_TRUE((w == 1.0f).all());
        EXPECT_EQ(rec.eta, 1.0f);
        EXPECT_LT(rec.wo.z(), 0.0f);  // stays inside
        EXPECT_NEAR((rec.wo - reflectLocal(rec.wi)).norm(), 0.0f, 1e-7f);
    }
}

TEST(Dielectric, UnscaledEnergyIsConservedFromBothSides) {
    // Expected value of weight * eta^2 over the sampled event is F + (1 - F) = 1 at every angle,
    // from outside and from inside (with total internal reflection).
    auto bsdf = glass(1.33f, 1.0f);
    Uniform u(3);
    for (float deg : {5.0f, 45.0f, 85.0f, 95.0f, 130.0f, 175.0f}) {
        double sum = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            BSDFQueryRecord rec(direction(deg, 77.0f));
            Color3f w = bsdf->sample(rec, u.next2D());
            EXPECT_NEAR(rec.wo.norm(), 1.0f, 1e-5f);
            sum += w[0] * rec.eta * rec.eta;
        }
        EXPECT_NEAR(sum / n, 1.0, 1e-5) << deg;
    }
}
