/// \file integrator.h
/// \brief Integrator interface: radiance along a camera ray.
#pragma once

#include <nori/color.h>
#include <nori/object.h>
#include <nori/ray.h>

namespace nori {

class Scene;
class Sampler;

/// \brief Estimates the radiance arriving along a ray.
class Integrator : public NoriObject {
public:
    /// \brief Called once before rendering.
    virtual void preprocess(const Scene &scene) {}
    /// \brief Radiance estimate along \p ray.
    virtual Color3f Li(const Scene &scene, Sampler &sampler, const Ray3f &ray) const = 0;
    EClassType getClassType() const override { return EIntegrator; }
};

} // namespace nori
