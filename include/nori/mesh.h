/// \file mesh.h
/// \brief Triangle mesh: positions, faces and only the optional attributes its file has.
#pragma once

#include <nori/bbox.h>
#include <nori/dpdf.h>
#include <nori/object.h>
#include <array>
#include <vector>

namespace nori {

class BSDF;
class Emitter;

/// \brief A point drawn uniformly by area on a mesh.
struct MeshSample {
    Point3f p;
    Normal3f n;           ///< shading normal (interpolated vertex normals, else the geometric one)
    Normal3f ng;          ///< unit geometric normal
    float offset = 0.0f;  ///< spawn offset of p (see spawnOffset() in ray.h)
    float pdf = 0.0f;     ///< density per unit area: 1 / surfaceArea()
};

/// \brief Vertex and face buffers of a triangle mesh (what an OBJ file yields).
struct MeshData {
    std::vector<Point3f> positions;
    std::vector<Normal3f> normals;  ///< empty, or one per position
    std::vector<Point2f> uvs;       ///< empty, or one per position
    std::vector<std::array<uint32_t, 3>> faces;
};

/// \brief A triangle mesh in world space with its BSDF and, for an area light, its emitter.
class Mesh : public NoriObject {
public:
    Mesh();
    /// \brief A mesh from buffers already in world space (used by tests and tools).
    Mesh(MeshData data, const std::string &name);
    ~Mesh() override;

    uint32_t triangleCount() const { return uint32_t(m_data.faces.size()); }
    uint32_t vertexCount() const { return uint32_t(m_data.positions.size()); }
    const std::vector<Point3f> &positions() const { return m_data.positions; }
    const std::vector<Normal3f> &normals() const { return m_data.normals; }
    const std::vector<Point2f> &uvs() const { return m_data.uvs; }
    const std::vector<std::array<uint32_t, 3>> &faces() const { return m_data.faces; }
    bool hasNormals() const { return !m_data.normals.empty(); }
    bool hasUVs() const { return !m_data.uvs.empty(); }

    /// \brief Corner \p corner (0..2) of triangle \p index.
    const Point3f &vertex(uint32_t index, int corner) const { return m_data.positions[m_data.faces[index][corner]]; }
    BoundingBox3f triangleBounds(uint32_t index) const;
    float triangleArea(uint32_t index) const;
    /// \brief Unit geometric normal (zero vector for a degenerate triangle).
    Normal3f geometricNormal(uint32_t index) const;
    const BoundingBox3f &bbox() const { return m_bbox; }

    const BSDF *bsdf() const { return m_bsdf.get(); }
    /// \brief The area light on this mesh, or null.
    const Emitter *emitter() const { return m_emitter.get(); }
    bool isEmitter() const { return m_emitter != nullptr; }

    /// \brief Total area (computed by activate() for a mesh that emits; 0 before).
    float surfaceArea() const { return m_area; }
    /// \brief A point uniform by area: a triangle chosen in proportion to its area, then uniform
    /// barycentrics; the first sample dimension serves both. Needs activate() on an emitting mesh.
    void samplePosition(const Point2f &sample, MeshSample &out) const;
    /// \brief Point, normals and spawn offset at barycentrics (b1, b2) of triangle \p index.
    void surfacePoint(uint32_t index, float b1, float b2, MeshSample &out) const;
    const std::string &name() const { return m_name; }

    void addChild(std::unique_ptr<NoriObject> child) override;
    void activate() override;
    EClassType getClassType() const override { return EMesh; }
    std::string toString() const override;

protected:
    /// \brief Install buffers (already transformed to world space) and compute the bbox.
    void setData(MeshData data);

    MeshData m_data;
    std::string m_name;
    BoundingBox3f m_bbox;
    std::unique_ptr<BSDF> m_bsdf;
    std::unique_ptr<Emitter> m_emitter;
    DiscretePDF m_areaPDF;  ///< over triangles, by area (emitting meshes only)
    float m_area = 0.0f;
};

} // namespace nori
