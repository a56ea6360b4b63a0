/// \file mesh.cpp
/// \brief Triangle mesh: geometry queries, BSDF and emitter children, uniform sampling by area.
#include <nori/bsdf.h>
#include <nori/emitter.h>
#include <nori/mesh.h>
#include <nori/warp.h>

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
    switch (child->getClassType()) {
    case EBSDF:
        if (m_bsdf) throw NoriException("{}: mesh already has a BSDF", child->location());
        m_bsdf.reset(static_cast<BSDF *>(child.release()));
        break;
    case EEmitter:
        if (m_emitter)
            throw NoriException("{}: mesh already has an emitter (declared at {}); a mesh holds at most one",
                                child->location(), m_emitter->location());
        m_emitter.reset(static_cast<Emitter *>(child.release()));
        break;
    default: NoriObject::addChild(std::move(child));
    }
}

void Mesh::activate() {
    if (!m_bsdf) {
        PropertyList props;
        props.setLocation(location());
        std::unique_ptr<NoriObject> bsdf = NoriObjectFactory::createInstance(EBSDF, "diffuse", props);
        m_bsdf.reset(static_cast<BSDF *>(bsdf.release()));
    }
    if (m_emitter) {
        m_areaPDF.clear();
        m_areaPDF.reserve(triangleCount());
        for (uint32_t f = 0; f < triangleCount(); ++f) {
            float a = triangleArea(f);
            m_areaPDF.append(std::isfinite(a) ? a : 0.0f);
        }
        m_area = m_areaPDF.normalize();
        if (!(m_area > 0.0f) || !std::isfinite(m_area))
            throw NoriException("{}: the mesh '{}' carries an emitter but has no area to emit from", location(), m_name);
        m_emitter->setMesh(this);
    }
}

void Mesh::surfacePoint(uint32_t index, float b1, float b2, MeshSample &out) const {
    const auto &face = m_data.faces[index];
    const Point3f &p0 = m_data.positions[face[0]], &p1 = m_data.positions[face[1]], &p2 = m_data.positions[face[2]];
    float b0 = 1.0f - b1 - b2;
    out.p = b0 * p0 + b1 * p1 + b2 * p2;
    out.ng = geometricNormal(index);
    out.n = out.ng;
    if (hasNormals()) {
        const auto &N = m_data.normals;
        Normal3f ns = b0 * N[face[0]] + b1 * N[face[1]] + b2 * N[face[2]];
        float len = ns.norm();
        if (len > 0.0f && std::isfinite(len)) out.n = ns / len;
    }
    out.offset = spawnOffset(p0, p1, p2, out.p, interpolationError(p0, p1, p2, b0, b1, b2), out.ng);
}

void Mesh::samplePosition(const Point2f &sample, MeshSample &out) const {
    float u = sample.x();
    uint32_t index = uint32_t(m_areaPDF.sampleReuse(u));
    Point2f b = squareToUniformTriangle(Point2f(u, sample.y()));
    surfacePoint(index, b.x(), b.y(), out);
    out.pdf = 1.0f / m_area;
}

std::string Mesh::toString() const {
    return fmt::format("Mesh[name=\"{}\", vertices={}, triangles={}, normals={}, uvs={}, emitter={}]", m_name,
                       vertexCount(), triangleCount(), hasNormals(), hasUVs(),
                       m_emitter ? m_emitter->toString() : std::string("none"));
}

} // namespace nori
