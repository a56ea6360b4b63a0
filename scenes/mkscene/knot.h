/// \file knot.h
/// \brief The default scene's centrepiece: a ridged, beaded trefoil-knot tube.
#pragma once

#include "mesh_builder.h"

namespace mkscene {

/// \brief A (2,3) torus knot swept by a closed tube of \p rings rings x \p around vertices,
/// with spiral ridges and beads, scaled to a footprint of 1 unit (x, z in [-0.5, 0.5]) and
/// lifted so its lowest point is at y = \p floorY + \p gap.
void buildKnot(MeshBuilder &m, int rings, int around, double floorY, double gap);

} // namespace mkscene
