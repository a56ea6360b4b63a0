/// \file perspective.cpp
/// \brief Pinhole perspective camera (Nori's `perspective`).
#include <nori/camera.h>
#include <nori/rfilter.h>

namespace nori {

Camera::~Camera() = default;

void Camera::addChild(std::unique_ptr<NoriObject> child) {
    if (child->getClassType() != EReconstructionFilter) NoriObject::addChild(std::move(child));
    if (m_filter) throw NoriException("{}: camera already has a reconstruction filter", child->location());
    m_filter.reset(static_cast<ReconstructionFilter *>(child.release()));
}

void Camera::activate() {
    if (!m_filter) {
        PropertyList props;
        props.setLocation(location());
        m_filter.reset(static_cast<ReconstructionFilter *>(
            NoriObjectFactory::createInstance(EReconstructionFilter, "gaussian", props).release()));
    }
}

/// \brief Camera looking down +z in its local frame; `toWorld` places it in the scene.
class PerspectiveCamera : public Camera {
public:
    explicit PerspectiveCamera(const PropertyList &props) {
        m_outputSize = Vector2i(props.getInteger("width", 1280), props.getInteger("height", 720));
        // Guard the renderer's memory: 16k x 16k is far beyond any sensible offline image here.
        constexpr int MaxSide = 16384;
        for (const char *name : {"width", "height"}) {
            int value = props.getInteger(name, 1);
            if (value <= 0 || value > MaxSide)
                props.fail(name, fmt::format("camera {} must be in [1, {}], got {}", name, MaxSide, value));
        }
        m_fov = props.getFloat("fov", 30.0f);
        if (!(m_fov > 0.0f && m_fov < 180.0f))
            props.fail("fov", fmt::format("camera fov must be in (0, 180) degrees, got {}", m_fov));
        m_nearClip = props.getFloat("nearClip", 1e-4f);
        m_farClip = props.getFloat("farClip", 1e4f);
        if (!(m_nearClip > 0.0f) || !(m_farClip > m_nearClip) || !std::isfinite(m_farClip))
            props.fail("nearClip", fmt::format("camera needs 0 < nearClip < farClip < inf, got {} and {}",
                                               m_nearClip, m_farClip));
        m_toWorld = props.getTransform("toWorld", Transform());
    }

    Color3f sampleRay(Ray3f &ray, const Point2f &samplePosition, const Point2f &) const override {
        // Image position -> point on the z=1 plane in camera space. As in Nori, `fov` is the
        // horizontal field of view and camera-space +x points to the image's left.
        float aspect = float(m_outputSize.x()) / float(m_outputSize.y());
        float tanHalf = std::tan(degToRad(0.5f * m_fov));
        float x = (1.0f - 2.0f * samplePosition.x() / float(m_outputSize.x())) * tanHalf;
        float y = (1.0f - 2.0f * samplePosition.y() / float(m_outputSize.y())) * tanHalf / aspect;
        Vector3f d = Vector3f(x, y, 1.0f).normalized();
        float invZ = 1.0f / d.z();
        ray.o = m_toWorld.applyPoint(Point3f::Zero());
        ray.d = m_toWorld.applyVector(d).normalized();
        // The transform may scale; clip distances are along the unit camera-space direction.
        ray.mint = m_nearClip * invZ;
        ray.maxt = m_farClip * invZ;
        ray.update();
        return Color3f(1.0f);
    }

    std::string toString() const override {
        return fmt::format("PerspectiveCamera[size={}x{}, fov={}, clip=[{}, {}]]", m_outputSize.x(),
                           m_outputSize.y(), m_fov, m_nearClip, m_farClip);
    }

private:
    float m_fov, m_nearClip, m_farClip;
    Transform m_toWorld;
};

NORI_REGISTER_CLASS(PerspectiveCamera, "perspective", ECamera);

} // namespace nori
