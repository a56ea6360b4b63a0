/// \file test_transform.cpp
/// \brief Tests of Transform: a translation composed with its inverse is the identity; lookAt at
/// every scale.
#include <gtest/gtest.h>
#include <nori/transform.h>

using namespace nori;

TEST(Transform, TranslateThenInverseIsIdentity) {
    Transform t = Transform::translate(Vector3f(1, 2, 3));
    Point3f p = t.applyPoint(Point3f(0, 0, 0));
    EXPECT_FLOAT_EQ(p.x(), 1);
    EXPECT_FLOAT_EQ(p.z(), 3);
    Point3f q = t.inverse().applyPoint(p);
    EXPECT_NEAR(q.norm(), 0.0f, 1e-6f);
}

// The camera looks along +z of its frame: lookAt maps (0, 0, 1) to the unit direction from the
// origin to the target, at any scale of the scene (|d|^2 underflows below ~1e-19 and overflows
// above ~1e19 in float; the direction is still well defined).
TEST(Transform, LookAtWorksAtEveryScale) {
    for (float scale : {1e-30f, 1e-3f, 1.0f, 1e6f, 1e37f}) {
        const Point3f origin = scale * Point3f(0, 3, 4), target(0, 0, 0);
        Transform t = Transform::lookAt(origin, target, Vector3f(0, 1, 0));
        const Vector3f d = t.applyVector(Vector3f(0, 0, 1));
        EXPECT_NEAR(d.x(), 0.0f, 1e-6f) << scale;
        EXPECT_NEAR(d.y(), -0.6f, 1e-6f) << scale;
        EXPECT_NEAR(d.z(), -0.8f, 1e-6f) << scale;
        EXPECT_EQ(t.applyPoint(Point3f(0, 0, 0)), origin) << scale;
    }
    EXPECT_THROW(Transform::lookAt(Point3f(1, 2, 3), Point3f(1, 2, 3), Vector3f(0, 1, 0)), NoriException);
    EXPECT_THROW(Transform::lookAt(Point3f(0, 0, 0), Point3f(0, 1, 0), Vector3f(0, 2, 0)), NoriException);
    EXPECT_THROW(Transform::lookAt(Point3f(0, 0, 0), Point3f(0, 0, 1), Vector3f(0, 0, 0)), NoriException);
}
