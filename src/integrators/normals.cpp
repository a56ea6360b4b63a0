/// \file normals.cpp
/// \brief Shows the absolute shading normal as a colour; black where the ray escapes.
#include <nori/scene.h>

namespace nori {

class NormalIntegrator : public Integrator {
public:
    explicit NormalIntegrator(const PropertyList &) {}

    Color3f Li(const Scene &scene, Sampler &, const Ray3f &ray) const override {
        Intersection its;
        if (!scene.rayIntersect(ray, its)) return Color3f(0.0f);
        return its.shFrame.n.cwiseAbs().array();
    }

    std::string toString() const override { return "NormalIntegrator[]"; }
};

NORI_REGISTER_CLASS(NormalIntegrator, "normals", EIntegrator);

} // namespace nori
