/// \file shape_generators.h
/// \brief One generator per shape (each in its own source file), registered in registry.cpp.
/// Every generator honours GenParams::triangles approximately and is a pure function of
/// its parameters.
#pragma once

#include "scene_generator.h"

namespace nori::gen {

GeneratedScene generateCity(const GenParams &params);
GeneratedScene generateGrass(const GenParams &params);
GeneratedScene generateHeightfield(const GenParams &params);
GeneratedScene generateDisplacedSphere(const GenParams &params);
GeneratedScene generateRoom(const GenParams &params);
GeneratedScene generateWide(const GenParams &params);
GeneratedScene generateTabletop(const GenParams &params);
GeneratedScene generateStadium(const GenParams &params);
GeneratedScene generateCoplanar(const GenParams &params);
GeneratedScene generateForest(const GenParams &params);
GeneratedScene generateOffice(const GenParams &params);
GeneratedScene generateTowers(const GenParams &params);
GeneratedScene generateClutter(const GenParams &params);
GeneratedScene generateHair(const GenParams &params);
GeneratedScene generateSparse(const GenParams &params);
GeneratedScene generatePark(const GenParams &params);
GeneratedScene generateSpeck(const GenParams &params);

} // namespace nori::gen
