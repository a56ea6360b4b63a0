/// \file test_microfacet.cpp
/// \brief The microfacet BSDF: its sampling agrees with eval and pdf, pdf integrates to the
/// probability that sampling succeeds, reciprocity, energy, limits and bad parameters.
#include "bsdf_util.h"
#include <error_of.h>
#include <gtest/gtest.h>
#include <nori/frame.h>
#include <nori/fresnel.h>

using namespace nori;
using namespace nori::test;

namespace {

std::unique_ptr<BSDF> microfacet(float alpha, const Color3f &kd, float intIOR = 1.5f, float extIOR = 1.000277f) {
    PropertyList props;
    props.setFloat("alpha", alpha);
    props.setColor("kd", kd);
    props.setFloat("intIOR", intIOR);
    props.setFloat("extIOR", extIOR);
    return makeBSDF("microfacet", props);
}

/// Integral of pdf(wi, .) over the upper hemisphere, midpoint rule in (cos theta, phi).
double integratePdf(const BSDF &bsdf, const Vector3f &wi, int nz = 800, int nphi = 800) {
    double sum = 0.0;
    for (int i = 0; i < nz; ++i) {
        double z = (i + 0.5) / nz, r = std::sqrt(1.0 - z * z);
        for (int j = 0; j < nphi; ++j) {
            double phi = (j + 0.5) * 2.0 * M_PI / nphi;
            Vector3f wo(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
            sum += bsdf.pdf(BSDFQueryRecord(wi, wo, EMeasure::SolidAngle));
        }
    }
    return sum * (1.0 / nz) * (2.0 * M_PI / nphi);
}

struct Config {
    float alpha;
    Color3f kd;
};
const Config kConfigs[] = {{0.1f, Color3f(0.0f)}, {0.3f, Color3f(0.2f, 0.1f, 0.6f)}, {0.6f, Color3f(0.4f, 0.2f, 0.3f)}};

} // namespace

TEST(Microfacet, NoriDefaultsAndDiffuseFlag) {
    auto bsdf = makeBSDF("microfacet");
    EXPECT_EQ(bsdf->toString(), "Microfacet[alpha=0.1, intIOR=1.5046, extIOR=1.000277, kd=(0.5, 0.5, 0.5), ks=0.5]");
    EXPECT_TRUE(bsdf->isDiffuse());
}

TEST(Microfacet, RejectsBadParameters) {
    struct Bad {
        const char *name;
        float value;
        const char *message;
    };
    for (const Bad &b : {Bad{"alpha", 0.0f, "alpha must be positive, got 0"},
                         Bad{"alpha", -0.1f, "alpha must be positive, got -0.1"},
                         Bad{"intIOR", 0.0f, "intIOR must be positive"},
                         Bad{"extIOR", -1.0f, "extIOR must be positive"}}) {
        PropertyList props;
        props.setFloat(b.name, b.value, "rough.xml:4");
        std::string message = errorOf([&] { makeBSDF("microfacet", props); });
        EXPECT_EQ(message.rfind("rough.xml:4: ", 0), 0u) << message;
        EXPECT_NE(message.find(b.message), std::string::npos) << message;
    }
    PropertyList props;
    props.setColor("kd", Color3f(0.5f, 1.2f, 0.0f), "rough.xml:5");
    EXPECT_NE(errorOf([&] { makeBSDF("microfacet", props); }).find("kd components must be in [0, 1]"),
              std::string::npos);
}

TEST(Microfacet, SampleWeightIsEvalCosOverPdf) {
    Uniform u(11);
    for (const Config &c : kConfigs) {
        auto bsdf = microfacet(c.alpha, c.kd);
        for (float deg : {0.0f, 40.0f, 75.0f}) {
            for (int i = 0; i < 2000; ++i) {
                BSDFQueryRecord rec(direction(deg, 15.0f));
                Color3f w = bsdf->sample(rec, u.next2D());
                if ((w == 0.0f).all()) continue;
                EXPECT_EQ(rec.measure, EMeasure::SolidAngle);
                EXPECT_EQ(rec.eta, 1.0f);
                Color3f expected = bsdf->eval(rec) * Frame::cosTheta(rec.wo) / bsdf->pdf(rec);
                EXPECT_NEAR((w - expected).abs().maxCoeff(), 0.0f, 1e-4f * expected.maxCoeff());
            }
        }
    }
}

TEST(Microfacet, PdfIntegratesToTheProbabilityThatSamplingSucceeds) {
    // Specular samples whose mirrored direction falls below the horizon are lost; pdf() leaves
    // them out too, so its integral is below 1 exactly by the lost fraction.
    Uniform u(5);
    for (const Config &c : kConfigs) {
        auto bsdf = microfacet(c.alpha, c.kd);
        for (float deg : {0.0f, 50.0f, 80.0f}) {
            Vector3f wi = direction(deg, 0.0f);
            const int n = 200000;
            int succeeded = 0;
            for (int i = 0; i < n; ++i) {
                BSDFQueryRecord rec(wi);
                succeeded += (bsdf->sample(rec, u.next2D()) != 0.0f).any();
            }
            double p = double(succeeded) / n;
            EXPECT_NEAR(integratePdf(*bsdf, wi), p, 4.0 * std::sqrt(p * (1 - p) / n) + 2e-3)
                << "alpha " << c.alpha << " at " << deg;
        }
    }
}

TEST(Microfacet, EvalIsReciprocalAndZeroBelowTheHorizon) {
    auto bsdf = microfacet(0.25f, Color3f(0.1f, 0.2f, 0.3f));
    Uniform u(9);
    for (int i = 0; i < 1000; ++i) {
        Vector3f a = direction(89.0f * u.next(), 360.0f * u.next()), b = direction(89.0f * u.next(), 360.0f * u.next());
        Color3f ab = bsdf->eval(BSDFQueryRecord(a, b, EMeasure::SolidAngle));
        Color3f ba = bsdf->eval(BSDFQueryRecord(b, a, EMeasure::SolidAngle));
        EXPECT_LE((ab - ba).abs().maxCoeff(), 1e-5f * ab.maxCoeff());
        EXPECT_TRUE((ab > 0.0f).all());
    }
    Vector3f up = direction(30.0f), down = direction(120.0f);
    EXPECT_TRUE((bsdf->eval(BSDFQueryRecord(up, down, EMeasure::SolidAngle)) == 0.0f).all());
    EXPECT_TRUE((bsdf->eval(BSDFQueryRecord(down, up, EMeasure::SolidAngle)) == 0.0f).all());
    EXPECT_TRUE((bsdf->eval(BSDFQueryRecord(up, up, EMeasure::Discrete)) == 0.0f).all());
    EXPECT_EQ(bsdf->pdf(BSDFQueryRecord(up, down, EMeasure::SolidAngle)), 0.0f);
    BSDFQueryRecord rec(down);
    EXPECT_TRUE((bsdf->sample(rec, Point2f(0.5f, 0.5f)) == 0.0f).all());
}

TEST(Microfacet, KdOnlyIsLambertian) {
    // max(kd) = 1 makes ks = 0: eval = kd/pi, pdf = cos/pi, and every sample returns kd.
    Color3f kd(1.0f, 0.5f, 0.25f);
    auto bsdf = microfacet(0.2f, kd);
    Uniform u(2);
    for (int i = 0; i < 1000; ++i) {
        BSDFQueryRecord rec(direction(60.0f * u.next(), 360.0f * u.next()));
        Color3f w = bsdf->sample(rec, u.next2D());
        EXPECT_LE((w - kd).abs().maxCoeff(), 1e-5f);
        EXPECT_LE((bsdf->eval(rec) - kd * InvPi).abs().maxCoeff(), 1e-6f);
        EXPECT_NEAR(bsdf->pdf(rec), Frame::cosTheta(rec.wo) * InvPi, 1e-6f);
    }
}

TEST(Microfacet, SpecularPartFollowsFresnelAndConservesEnergy) {
    // kd = 0: only the coating. A nearly smooth coating (alpha = 0.05) reflects close to the
    // Fresnel reflectance of a flat interface; equal indices mean no interface and no reflection.
    Uniform u(4);
    auto same = microfacet(0.3f, Color3f(0.0f), 1.2f, 1.2f);
    auto coat = microfacet(0.05f, Color3f(0.0f), 1.5f, 1.0f);
    for (float deg : {0.0f, 30.0f, 60.0f}) {
        BSDFQueryRecord rec(direction(deg));
        EXPECT_TRUE((same->sample(rec, Point2f(0.3f, 0.6f)) == 0.0f).all());
        double albedo = 0.0;
        const int n = 100000;
        for (int i = 0; i < n; ++i) {
            BSDFQueryRecord r(direction(deg));
            albedo += coat->sample(r, u.next2D())[0];
        }
        albedo /= n;
        EXPECT_NEAR(albedo, fresnelDielectric(std::cos(degToRad(deg)), 1.0f, 1.5f), 0.003) << deg;
    }
}
