/// \file test_diffuse.cpp
/// \brief The Lambertian BSDF: sampling matches eval and pdf, the pdf is normalised, albedo.
#include "bsdf_util.h"
#include <gtest/gtest.h>
#include <nori/frame.h>

using namespace nori;
using namespace nori::test;

TEST(Diffuse, SampleWeightIsEvalCosOverPdfAndTheAlbedo) {
    Color3f albedo(0.8f, 0.4f, 0.1f);
    PropertyList props;
    props.setColor("albedo", albedo);
    auto bsdf = makeBSDF("diffuse", props);
    EXPECT_TRUE(bsdf->isDiffuse());
    Uniform u(1);
    for (int i = 0; i < 2000; ++i) {
        BSDFQueryRecord rec(direction(89.0f * u.next(), 360.0f * u.next()));
        Color3f w = bsdf->sample(rec, u.next2D());
        ASSERT_GT(Frame::cosTheta(rec.wo), 0.0f);
        EXPECT_EQ(rec.measure, EMeasure::SolidAngle);
        Color3f expected = bsdf->eval(rec) * Frame::cosTheta(rec.wo) / bsdf->pdf(rec);
        EXPECT_LE((w - expected).abs().maxCoeff(), 1e-5f);
        EXPECT_LE((w - albedo).abs().maxCoeff(), 1e-6f);
    }
}

TEST(Diffuse, PdfIntegratesToOneAndEvalIsReciprocal) {
    auto bsdf = makeBSDF("diffuse");
    Vector3f wi = direction(35.0f, 80.0f);
    double sum = 0.0;
    const int n = 400;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double z = (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = (j + 0.5) * 2 * M_PI / n;
            Vector3f wo(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
            BSDFQueryRecord rec(wi, wo, EMeasure::SolidAngle);
            sum += bsdf->pdf(rec);
            EXPECT_EQ(bsdf->eval(rec)[0], bsdf->eval(BSDFQueryRecord(wo, wi, EMeasure::SolidAngle))[0]);
        }
    EXPECT_NEAR(sum * (1.0 / n) * (2 * M_PI / n), 1.0, 1e-4);
    EXPECT_NEAR(bsdf->eval(BSDFQueryRecord(wi, direction(10.0f), EMeasure::SolidAngle))[0], 0.5f * InvPi, 1e-7f);
    EXPECT_EQ(bsdf->pdf(BSDFQueryRecord(wi, direction(100.0f), EMeasure::SolidAngle)), 0.0f);
}
