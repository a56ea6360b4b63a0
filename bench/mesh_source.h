/// \file mesh_source.h
/// \brief Where nori-bench gets its geometry: OBJ files, a Nori scene, or a generated mesh.
#pragma once

#include <nori/camera.h>
#include <nori/mesh.h>
#include <nori/scene.h>
#include <scene_generator.h>
#include <memory>
#include <string>
#include <vector>

namespace nori::bench {

/// \brief The geometry (and, for a scene, the camera) of one benchmark case.
struct BenchInput {
    std::string name;                            ///< file name as given, or "generated"
    std::vector<std::unique_ptr<Mesh>> ownedMeshes;  ///< bare meshes (--mesh, generated)
    std::unique_ptr<Scene> scene;                ///< --scene: owns its meshes and camera
    std::unique_ptr<Camera> ownedCamera;         ///< a generated scene's camera
    double loadMs = 0.0;

    /// \brief The meshes to measure, in the accel's global triangle order.
    std::vector<const Mesh *> meshPointers() const;
    /// \brief The scene's camera; null for bare meshes (an automatic framing camera is used).
    const Camera *camera() const { return scene ? &scene->camera() : ownedCamera.get(); }
    uint64_t triangleCount() const;
};

/// \brief Loads benchmark inputs.
class MeshSource {
public:
    /// \brief An OBJ file (.obj or .obj.gz) through nori::loadObjFile; load_ms is its time.
    static BenchInput loadMesh(const std::string &path);
    /// \brief A Nori scene file: every mesh and the camera, nothing else (loadSceneGeometry:
    /// the bench never shades, so scenes whose integrators, BSDFs or emitters this build
    /// lacks load too).
    static BenchInput loadScene(const std::string &path);
    /// \brief A generated scene (scenes/generators): its mesh and its camera. The name is
    /// "shape:SHAPE" (with ":N" triangles when not the shape's default).
    static BenchInput generatedShape(const std::string &shape, const gen::GenParams &params);
    /// \brief A deterministic generated mesh (a bumpy sphere over a ground plane, ~10k
    /// triangles) so that --quick runs without any file.
    static BenchInput generated();
};

} // namespace nori::bench
