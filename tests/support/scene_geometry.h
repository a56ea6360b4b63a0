/// \file scene_geometry.h
/// \brief Loads only the geometry and the camera of a Nori scene file, so that scenes whose
/// integrators, BSDFs or emitters this build does not have (yet) can still be measured and
/// tested. The scene file itself is never modified or copied anywhere permanent.
#pragma once

#include <nori/scene.h>
#include <memory>
#include <string>

namespace nori {

/// \brief Parses \p path keeping only its <mesh> elements (without their <bsdf> and
/// <emitter> children) and its <camera>, with a `normals` integrator and brute-force accel
/// (never traced: callers build their own accelerators from the meshes). Mesh files resolve
/// against the scene's folder, then fileResolver(). Throws NoriException on any problem.
std::unique_ptr<Scene> loadSceneGeometry(const std::string &path);

} // namespace nori
