/// \file scene.cpp
/// \brief The scene: collects its children, builds the accelerator, counts rays.
#include <nori/scene.h>

namespace nori {

namespace {
// Per-thread counter: a block is rendered by one thread, so the renderer can attribute
// rays to blocks without contended atomics.
thread_local Scene::RayCounts t_rayCounts;

template <typename T> std::unique_ptr<T> downcast(std::unique_ptr<NoriObject> object) {
    return std::unique_ptr<T>(static_cast<T *>(object.release()));
}
} // namespace

Scene::Scene(const PropertyList &) {}
Scene::~Scene() = default;

Scene::RayCounts Scene::threadRayCounts() { return t_rayCounts; }

bool Scene::rayIntersect(const Ray3f &ray, Intersection &its) const {
    ++t_rayCounts.closestHit;
    return m_accel->rayIntersect(ray, its, false);
}

bool Scene::rayIntersect(const Ray3f &ray) const {
    ++t_rayCounts.shadow;
    return m_accel->occluded(ray);
}

void Scene::addChild(std::unique_ptr<NoriObject> child) {
    auto duplicate = [&](const char *what) {
        throw NoriException("{}: the scene already has {}", child->location(), what);
    };
    switch (child->getClassType()) {
    case EMesh: m_meshes.push_back(downcast<Mesh>(std::move(child))); break;
    case EEmitter:
        throw NoriException("{}: an <emitter> must be nested in the <mesh> it covers (only area lights exist)",
                            child->location());
    case EAccel:
        if (m_accel) duplicate("an accel");
        m_accel = downcast<Accel>(std::move(child));
        break;
    case ECamera:
        if (m_camera) duplicate("a camera");
        m_camera = downcast<Camera>(std::move(child));
        break;
    case ESampler:
        if (m_sampler) duplicate("a sampler");
        m_sampler = downcast<Sampler>(std::move(child));
        break;
    case EIntegrator:
        if (m_integrator) duplicate("an integrator");
        m_integrator = downcast<Integrator>(std::move(child));
        break;
    default: NoriObject::addChild(std::move(child));
    }
}

void Scene::activate() {
    if (!m_camera) throw NoriException("{}: the scene has no <camera>", location());
    if (!m_integrator) throw NoriException("{}: the scene has no <integrator>", location());
    if (!m_accel || !m_sampler) throw NoriException("{}: internal error: no accel or sampler", location());
    for (const auto &mesh : m_meshes) {
        m_accel->addMesh(mesh.get());
        if (mesh->emitter()) m_emitters.push_back(mesh->emitter());
    }
    m_accel->build();
    m_integrator->preprocess(*this);
}

std::string Scene::toString() const {
    std::string meshes;
    for (const auto &m : m_meshes) meshes += "\n  " + m->toString();
    return fmt::format("Scene[\n  {}\n  {}\n  {}\n  {}{}\n]", m_accel->toString(), m_camera->toString(),
                       m_sampler->toString(), m_integrator->toString(), meshes);
}

NORI_REGISTER_CLASS(Scene, "scene", EScene);

} // namespace nori
