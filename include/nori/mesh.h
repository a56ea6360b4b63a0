/// \file mesh.h
/// \brief Triangle mesh: positions, faces and only the optional attributes its file has.
#pragma once

#include <nori/bbox.h>
#include <nori/object.h>
#include <array>
#include <vector>

namespace nori {

class BSDF;

/// \brief Vertex and face buffers of a triangle mesh (what an OBJ file yields).
struct MeshData {
    std::vector<Point3f> positions;
    std::vector<Normal3f> normals;  ///< empty, or one per position
    std::vector<Point2f> uvs;       ///< empty, or one per position
    std::vector<std::array<uint32_t, 3>> faces;
};

/// \brief A triangle mesh in world space with its BSDF.
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
};

} // namespace nori
