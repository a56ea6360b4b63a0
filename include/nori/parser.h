/// \file parser.h
/// \brief Loads Nori's XML scene format.
#pragma once

#include <nori/object.h>

namespace nori {

class Scene;

/// \brief Command-line changes applied while a scene is parsed.
struct SceneOverrides {
    std::string accelType;    ///< replaces the scene's accel type (empty: keep it)
    PropertyList accelProps;  ///< added to / replacing the accel's properties
    int sampleCount = 0;      ///< replaces the sampler's sampleCount (0: keep it)
};

/// \brief Parse \p path and return the activated root object. Relative file names inside
/// resolve against the scene's folder first, then fileResolver(). Every problem throws a
/// NoriException whose message starts with "FILE:LINE:COL:".
std::unique_ptr<NoriObject> loadFromXML(const std::string &path, const SceneOverrides &overrides = {});

/// \brief The name of the root element of \p path ("scene", "test", ...), read without building
/// any object; XML errors throw as in loadFromXML().
std::string rootElementName(const std::string &path);

/// \brief loadFromXML() for a file whose root must be a <scene>.
std::unique_ptr<Scene> loadScene(const std::string &path, const SceneOverrides &overrides = {});

} // namespace nori
