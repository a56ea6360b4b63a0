/// \file mesh_source.h
/// \brief Where nori-bench gets its geometry: OBJ files, a Nori scene, or a generated mesh.
#pragma once

#include <nori/camera.h>
#include <nori/mesh.h>
#include <memory>
#include <string>
#include <vector>

namespace nori::bench {

/// \brief The geometry (and, for a scene, the camera) of one benchmark case.
struct BenchInput {
    std::string name;                            ///< file name as given, or "generated"
    std::vector<std::unique_ptr<Mesh>> meshes;
    std::unique_ptr<Camera> camera;              ///< the scene's camera; null for bare meshes
    double loadMs = 0.0;

    std::vector<const Mesh *> meshPointers() const;
    uint64_t triangleCount() const;
};

/// \brief Loads benchmark inputs.
class MeshSource {
public:
    /// \brief An OBJ file (.obj or .obj.gz), timed. Uses the project's OBJ loader when it is
    /// built in, otherwise a minimal reader of v and f records.
    static BenchInput loadMesh(const std::string &path);
    /// \brief A Nori scene file: every mesh and the camera (needs the project's scene parser).
    static BenchInput loadScene(const std::string &path);
    /// \brief A deterministic generated mesh (a bumpy sphere over a ground plane, ~10k
    /// triangles) so that --quick runs without any file.
    static BenchInput generated();
    /// \brief Whether this build can read scenes.
    static bool hasSceneParser();
};

} // namespace nori::bench
