/// \file scene.h
/// \brief The scene: meshes, emitters, accelerator, camera, sampler and integrator.
#pragma once

#include <nori/accel.h>
#include <nori/camera.h>
#include <nori/emitter.h>
#include <nori/integrator.h>
#include <nori/sampler.h>

namespace nori {

/// \brief Root object of a scene file; owns everything in it.
class Scene : public NoriObject {
public:
    explicit Scene(const PropertyList &props);
    ~Scene() override;

    /// \brief Closest hit along \p ray (counts one ray).
    bool rayIntersect(const Ray3f &ray, Intersection &its) const;
    /// \brief Is anything in [ray.mint, ray.maxt]? (a shadow ray; counts one ray)
    bool rayIntersect(const Ray3f &ray) const;
    /// \brief Rays traced by the calling thread so far, by kind (the renderer takes differences).
    struct RayCounts {
        uint64_t closestHit = 0;  ///< rayIntersect(ray, its): camera rays and bounces
        uint64_t shadow = 0;      ///< rayIntersect(ray): any-hit (occlusion) queries
        uint64_t total() const { return closestHit + shadow; }
    };
    static RayCounts threadRayCounts();
    /// \brief threadRayCounts().total().
    static uint64_t threadRayCount() { return threadRayCounts().total(); }

    const Accel &accel() const { return *m_accel; }
    const Camera &camera() const { return *m_camera; }
    const Sampler &sampler() const { return *m_sampler; }
    const Integrator &integrator() const { return *m_integrator; }
    Integrator &integrator() { return *m_integrator; }
    const std::vector<std::unique_ptr<Mesh>> &meshes() const { return m_meshes; }
    const BoundingBox3f &bbox() const { return m_accel->bbox(); }
    /// \brief The emitters of all meshes, in mesh order.
    const std::vector<const Emitter *> &emitters() const { return m_emitters; }
    /// \brief One emitter chosen uniformly with \p u in [0, 1) (null if there is none); its
    /// probability is emitterChoicePdf().
    const Emitter *sampleEmitter(float u) const {
        if (m_emitters.empty()) return nullptr;
        size_t i = std::min(size_t(u * float(m_emitters.size())), m_emitters.size() - 1);
        return m_emitters[i];
    }
    float emitterChoicePdf() const { return m_emitters.empty() ? 0.0f : 1.0f / float(m_emitters.size()); }

    void addChild(std::unique_ptr<NoriObject> child) override;
    /// \brief Checks that camera and integrator exist and builds the accelerator.
    void activate() override;
    EClassType getClassType() const override { return EScene; }
    std::string toString() const override;

private:
    std::vector<std::unique_ptr<Mesh>> m_meshes;
    std::vector<const Emitter *> m_emitters;
    std::unique_ptr<Accel> m_accel;
    std::unique_ptr<Camera> m_camera;
    std::unique_ptr<Sampler> m_sampler;
    std::unique_ptr<Integrator> m_integrator;
};

} // namespace nori
