/// \file scene_writer.h
/// \brief Writes a generated scene as SHAPE.obj plus SHAPE.xml (a Nori scene that `nori`
/// renders as it is).
#pragma once

#include "scene_generator.h"
#include <string>

namespace nori::gen {

/// \brief Serialises a GeneratedScene to OBJ and Nori XML.
class SceneWriter {
public:
    /// \brief OBJ text: `v` lines with the shortest decimals that round-trip (the loaded mesh
    /// is bit-identical to the generated one) and 1-based `f` lines.
    static std::string objText(const MeshData &mesh, const std::string &comment);
    /// \brief Nori XML: the mesh \p objName with a diffuse BSDF, the camera, an `ao` (or
    /// `normals`) integrator and an independent sampler with \p spp samples.
    static std::string xmlText(const GeneratedScene &scene, const std::string &objName, const std::string &integrator,
                               int spp, const std::string &comment);
    /// \brief Write OUT_DIR/NAME.obj and OUT_DIR/NAME.xml as one transaction: both go to
    /// temporary files first and are renamed into place only when both are complete.
    /// Throws NoriException on any failure (no partial output is left behind).
    static void write(const GeneratedScene &scene, const std::string &outDir, const std::string &name,
                      const std::string &integrator, int spp, const std::string &comment);
};

} // namespace nori::gen
