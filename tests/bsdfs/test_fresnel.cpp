/// \file test_fresnel.cpp
/// \brief Fresnel reflectance against hand-computed values and its physical limits.
#include <gtest/gtest.h>
#include <nori/fresnel.h>

using namespace nori;

TEST(Fresnel, NormalIncidenceIsSquaredIndexContrast) {
    // At normal incidence both polarisations give ((n1 - n2) / (n1 + n2))^2.
    for (float n : {1.33f, 1.5f, 2.4f}) {
        float expected = (n - 1.0f) * (n - 1.0f) / ((n + 1.0f) * (n + 1.0f));
        EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, n), expected, 1e-6f) << n;
        EXPECT_NEAR(fresnelDielectric(-1.0f, 1.0f, n), expected, 1e-6f) << n;  // same from the inside
    }
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, 1.5f), 0.04f, 1e-6f);
}

TEST(Fresnel, HandComputedValueAt45Degrees) {
    // Air to n = 1.5 at 45 degrees, worked out in double precision from Snell's law
    // (sin(theta_t) = sin(45)/1.5): Rs = 0.0920134, Rp = 0.0084665, unpolarised average 0.0502399.
    EXPECT_NEAR(fresnelDielectric(std::cos(degToRad(45.0f)), 1.0f, 1.5f), 0.0502399f, 1e-6f);
}

TEST(Fresnel, EqualIndicesMeanNoInterface) {
    EXPECT_EQ(fresnelDielectric(0.3f, 1.4f, 1.4f), 0.0f);
    EXPECT_EQ(fresnelDielectric(-0.7f, 1.4f, 1.4f), 0.0f);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
    EXPECT_NEAR(fresnelDielectric(1e-7f, 1.0f, 1.5f), 1.0f, 1e-5f);
    EXPECT_NEAR(fresnelDielectric(0.0f, 1.0f, 1.5f), 1.0f, 1e-6f);
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
    // From inside glass (n = 1.5) the critical angle is asin(1/1.5) = 41.81 degrees.
    float critical = std::asin(1.0f / 1.5f);
    EXPECT_EQ(fresnelDielectric(-std::cos(critical + 0.01f), 1.0f, 1.5f), 1.0f);
    EXPECT_EQ(fresnelDielectric(-std::cos(degToRad(80.0f)), 1.0f, 1.5f), 1.0f);
    EXPECT_LT(fresnelDielectric(-std::cos(critical - 0.01f), 1.0f, 1.5f), 1.0f);
    // Swapping the media is the same as coming from the other side.
    EXPECT_EQ(fresnelDielectric(std::cos(critical + 0.01f), 1.5f, 1.0f), 1.0f);
}

TEST(Fresnel, SameReflectanceBothWaysThroughTheInterface) {
    // Stokes relations: a ray and its refracted partner see the same reflectance.
    for (float deg = 0.0f; deg < 89.0f; deg += 7.0f) {
        float cosI = std::cos(degToRad(deg));
        float sinT = std::sin(degToRad(deg)) / 1.5f;
        float cosT = std::sqrt(1.0f - sinT * sinT);
        EXPECT_NEAR(fresnelDielectric(cosI, 1.0f, 1.5f), fresnelDielectric(-cosT, 1.0f, 1.5f), 1e-5f) << deg;
    }
}

TEST(Fresnel, RefractionObeysSnellsLaw) {
    for (float deg : {0.0f, 10.0f, 30.0f, 60.0f, 85.0f}) {
        Vector3f wi(std::sin(degToRad(deg)), 0.0f, std::cos(degToRad(deg)));
        Vector3f wt;
        ASSERT_TRUE(refractLocal(wi, 1.0f / 1.5f, wt));
        EXPECT_NEAR(wt.norm(), 1.0f, 1e-6f);
        EXPECT_LT(wt.z(), 0.0f);
        // n1 sin(theta_i) = n2 sin(theta_t), and the tangential part turns to the other side.
        EXPECT_NEAR(1.0f * wi.x(), -1.5f * wt.x(), 1e-6f);
        EXPECT_EQ(wt.y(), 0.0f);
    }
    Vector3f wt;
    EXPECT_FALSE(refractLocal(Vector3f(std::sin(1.0f), 0.0f, -std::cos(1.0f)), 1.5f, wt));  // 57 deg inside glass
}
