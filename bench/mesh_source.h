/// \file mesh_source.h
/// \brief Where nori-bench gets its geometry: OBJ files, a Nori scene, or a generated mesh.
#pragma once

#include <nori/camera.h>
#include <nori/mesh.h>
#include <nori/scene.h>
#include <memory>
#include <string>
#include <vector>

namespace nori::bench {

/// \brief The geometry (and, for a scene, the camera) of one benchmark case.
struct BenchInput {
    std::string name;                            ///< file name as given, or "generated"
    std::vector<std::unique_ptr<Mesh>> ownedMeshes;  ///< bare meshes (--mesh, generated)
    std::unique_ptr<Scene> scene;                ///< --scene: owns its meshes and camera
    double loadMs = 0.0;

    /// \brief The meshes to measure, in the accel's global triangle order.
    std::vector<const Mesh *> meshPointers() const;
    /// \brief The scene's camera; null for bare meshes (an automatic framing camera is used).
    const Camera *camera() const { return scene ? &scene->camera() : nullptr; }
    uint64_t triangleCount() const;
};

/// \brief Loads benchmark inputs.
class MeshSource {
public:
    /// \brief An OBJ file (.obj or .obj.gz) through nori::loadObjFile; load_ms is its time.
    static BenchInput loadMesh(const std::string &path);
    /// \brief A Nori scene file: every mesh and the camera, through nori::loadScene (the
    /// scene's accel is replaced by brute force, whose build is free; it is never traced).
    static BenchInput loadScene(const std::string &path);
    /// \brief A deterministic generated mesh (a bumpy sphere over a ground plane, ~10k
    /// triangles) so that --quick runs without any file.
    static BenchInput generated();
};

} // namespace nori::bench
