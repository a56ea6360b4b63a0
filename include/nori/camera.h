/// \file camera.h
/// \brief Camera interface: turns image-plane samples into primary rays.
#pragma once

#include <nori/object.h>
#include <nori/ray.h>

namespace nori {

class ReconstructionFilter;

/// \brief Generates primary rays and owns the image's reconstruction filter.
class Camera : public NoriObject {
public:
    ~Camera() override;
    /// \brief Ray through image position \p samplePosition (pixels, centres at +0.5);
    /// returns the importance weight of the ray.
    virtual Color3f sampleRay(Ray3f &ray, const Point2f &samplePosition, const Point2f &apertureSample) const = 0;
    /// \brief Image size in pixels.
    const Vector2i &outputSize() const { return m_outputSize; }
    /// \brief The filter used to splat samples (gaussian unless the scene gives one).
    const ReconstructionFilter *reconstructionFilter() const { return m_filter.get(); }

    void addChild(std::unique_ptr<NoriObject> child) override;
    void activate() override;
    EClassType getClassType() const override { return ECamera; }

protected:
    Vector2i m_outputSize{0, 0};
    std::unique_ptr<ReconstructionFilter> m_filter;
};

} // namespace nori
