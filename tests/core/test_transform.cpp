/// \file test_transform.cpp
/// \brief Tests of Transform: a translation composed with its inverse is the identity.
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
