/// \file scene_generator.h
/// \brief Deterministic generated scenes of many shapes (city, grass, heightfield, ...),
/// used by nori-bench, the oracle tests and nori-genscene.
#pragma once

#include <nori/camera.h>
#include <nori/mesh.h>
#include <memory>
#include <string>
#include <vector>

namespace nori::gen {

/// \brief A rigid motion of a whole generated scene, mesh and camera alike (so the image stays
/// the same): a rotation by \p degrees about \p axis, then a translation by \p offset. It
/// tilts every axis-aligned wall and floor of a shape (a model placed at an angle), or moves
/// the scene far from the origin (a georeferenced model), where float coordinates are coarse.
struct Placement {
    Vector3f axis{0, 1, 0};
    float degrees = 0.0f;
    Vector3f offset{0, 0, 0};
    bool isIdentity() const { return degrees == 0.0f && offset == Vector3f(0, 0, 0); }
};

/// \brief What a generator is asked for: a triangle budget and a seed, and where the result goes.
struct GenParams {
    uint64_t triangles = 0;  ///< approximate triangle count; 0: the shape's default
    uint64_t seed = 1;       ///< everything random in the scene derives from it
    Placement placement{};   ///< applied after the shape is made (generateScene)
};

/// \brief A look-at pinhole camera (Nori's `perspective`, horizontal fov in degrees).
struct GenCamera {
    Point3f origin{0, 0, 1}, target{0, 0, 0};
    Vector3f up{0, 1, 0};
    float fov = 40.0f;
    int width = 640, height = 480;
    float nearClip = 1e-3f, farClip = 1e4f;
};

/// \brief One generated scene: a single mesh in world space, a camera that frames what the
/// shape is about, and the ambient-occlusion reach that makes its render readable.
struct GeneratedScene {
    std::string shape;        ///< registry name, e.g. "city"
    std::string description;  ///< one line: what it is and what it stresses
    MeshData mesh;
    GenCamera camera;
    std::string integrator = "ao";  ///< what makes its render legible: "ao" or "normals"
    float aoLength = 1.0f;          ///< `ao` integrator length for the written scene

    uint64_t triangleCount() const { return mesh.faces.size(); }
};

/// \brief Signature of one shape's generator.
using GeneratorFunction = GeneratedScene (*)(const GenParams &);

/// \brief A registered shape.
struct ShapeInfo {
    const char *name;
    const char *summary;
    uint64_t defaultTriangles;
    uint64_t minTriangles;  ///< below this the shape loses what makes it that shape
    GeneratorFunction generate;
};

/// \brief Every shape, in a fixed order.
const std::vector<ShapeInfo> &shapes();
/// \brief The shape called \p name, or nullptr.
const ShapeInfo *findShape(const std::string &name);
/// \brief Generate \p name, then move it by params.placement; throws NoriException for an
/// unknown shape, a triangle budget outside [minTriangles, 50M], a rotation about a zero or
/// non-finite axis or a non-finite offset.
GeneratedScene generateScene(const std::string &name, const GenParams &params = {});
/// \brief Move \p scene (mesh and camera) by \p placement.
void place(GeneratedScene &scene, const Placement &placement);
/// \brief The scene's camera as a Nori `perspective` camera object.
std::unique_ptr<Camera> makeCamera(const GenCamera &camera);
/// \brief Comma-separated shape names (for messages).
std::string shapeList();

} // namespace nori::gen
