#include <nori/bsdf.h>
#include <nori/mesh.h>

namespace nori {

Mesh::Mesh(MeshData data, const std::string &name) : m_name(name) { setData(std::move(data)); }

Mesh::Mesh() = default;
Mesh::~Mesh() = default;

void Mesh::setData(MeshData data) {
    m_data = std::move(data);
    m_bbox = BoundingBox3f();
    for (const Point3f &p : m_data.positions) m_bbox.expandBy(p);
}

BoundingBox3f Mesh::triangleBounds(uint32_t index) const {
    BoundingBox3f b;
    for (int c = 0; c < 3; ++c) b.expandBy(vertex(index, c));
    return b;
}

float Mesh::triangleArea(uint32_t index) const {
    return 0.5f * (vertex(index, 1) - vertex(index, 0)).cross(vertex(index, 2) - vertex(index, 0)).norm();
}

Normal3f Mesh::geometricNormal(uint32_t index) const {
    Normal3f n = (vertex(index, 1) - vertex(index, 0)).cross(vertex(index, 2) - vertex(index, 0));
    float len = n.norm();
    return len > 0.0f ? Normal3f(n / len) : Normal3f::Zero();
}

void Mesh::addChild(std::unique_ptr<NoriObject> child) {
    if (child->getClassType() != EBSDF) NoriObject::addChild(std::move(child));
    if (m_bsdf) throw NoriException("{}: mesh already has a BSDF", child->location());
    m_bsdf.reset(static_cast<BSDF *>(child.release()));
}

void Mesh::activate() {
    if (!m_bsdf) {
        PropertyList props;
        props.setLocation(location());
        std::unique_ptr<NoriObject> bsdf = NoriObjectFactory::createInstance(EBSDF, "diffuse", props);
        m_bsdf.reset(static_cast<BSDF *>(bsdf.release()));
    }
}

std::string Mesh::toString() const {
    return fmt::format("Mesh[name=\"{}\", vertices={}, triangles={}, normals={}, uvs={}]", m_name, vertexCount(),
                       triangleCount(), hasNormals(), hasUVs());
}

} // namespace nori
