/// \file test_camera.cpp
/// \brief Tests of the perspective camera: the centre ray, the horizontal field of view and the clip distances.
#include <gtest/gtest.h>
#include <nori/camera.h>

using namespace nori;

namespace {
std::unique_ptr<Camera> makeCamera(int w, int h, float fov, const Transform &toWorld) {
    PropertyList props;
    props.setLocation("test");
    props.setInteger("width", w);
    props.setInteger("height", h);
    props.setFloat("fov", fov);
    props.setFloat("nearClip", 0.5f);
    props.setFloat("farClip", 100.0f);
    props.setTransform("toWorld", toWorld);
    return std::unique_ptr<Camera>(
        static_cast<Camera *>(NoriObjectFactory::createInstance(NoriObject::ECamera, "perspective", props).release()));
}
} // namespace

TEST(Camera, CentreRayLooksAtTarget) {
    Point3f origin(1, 2, 3), target(4, 6, 3);
    auto camera = makeCamera(64, 32, 40, Transform::lookAt(origin, target, Vector3f(0, 0, 1)));
    Ray3f ray;
    camera->sampleRay(ray, Point2f(32, 16), Point2f(0.5f, 0.5f));
    EXPECT_NEAR((ray.o - origin).norm(), 0.0f, 1e-5f);
    EXPECT_NEAR(ray.d.dot((target - origin).normalized()), 1.0f, 1e-6f);
    EXPECT_NEAR(ray.mint, 0.5f, 1e-6f);  // the centre ray is the optical axis: clip distances unchanged
    EXPECT_NEAR(ray.maxt, 100.0f, 1e-4f);
}

TEST(Camera, FovIsHorizontalAndImageXGoesRight) {
    // Looking down -z with +y up: image right is world +x... for Nori's lookat, left = up x dir.
    auto camera = makeCamera(200, 100, 60, Transform::lookAt(Point3f(0, 0, 0), Point3f(0, 0, -1), Vector3f(0, 1, 0)));
    Ray3f left, right, top;
    camera->sampleRay(left, Point2f(0, 50), Point2f(0, 0));
    camera->sampleRay(right, Point2f(200, 50), Point2f(0, 0));
    camera->sampleRay(top, Point2f(100, 0), Point2f(0, 0));
    float horizontal = std::acos(left.d.normalized().dot(right.d.normalized()));
    EXPECT_NEAR(horizontal, degToRad(60.0f), 1e-4f);
    // The vertical extent follows from the aspect ratio: tan(v/2) = tan(30 deg) / 2.
    float vertical = 2.0f * std::acos(top.d.normalized().dot(Vector3f(0, 0, -1)));
    EXPECT_NEAR(std::tan(vertical / 2), std::tan(degToRad(30.0f)) / 2.0f, 1e-4f);
    EXPECT_LT(left.d.x(), 0.0f);  // pixel column 0 is on the viewer's left
    EXPECT_GT(right.d.x(), 0.0f);
    EXPECT_GT(top.d.y(), 0.0f);   // row 0 is the top of the image
}

TEST(Camera, ClipDistancesAreMeasuredAlongTheAxis) {
    auto camera = makeCamera(100, 100, 90, Transform());
    Ray3f ray;
    camera->sampleRay(ray, Point2f(0, 50), Point2f(0, 0));  // 45 degrees off axis
    EXPECT_NEAR(ray.mint * ray.d.normalized().z(), 0.5f, 1e-5f);
}
