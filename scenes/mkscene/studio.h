/// \file studio.h
/// \brief The default scene's set: pedestal, photo-studio cyclorama and softbox light panels.
#pragma once

#include "mesh_builder.h"

namespace mkscene {

/// \brief A round pedestal with bevelled edges: top at y = 0, bottom at y = -\p height.
/// Cap, bevels and side have their own vertices, so their creases stay sharp under
/// smooth normals.
void buildPedestal(MeshBuilder &m, double radius, double height, double bevel, int segments);

/// \brief A photo-studio sweep (cyclorama): a floor at \p floorY for z in [\p zBack, \p zFront]
/// that bends up with radius \p cove into a back wall at z = \p zBack rising to \p top,
/// over x in [-\p halfWidth, \p halfWidth]; its front faces the inside (+y, +z).
void buildCyclorama(MeshBuilder &m, double floorY, double zFront, double zBack, double cove, double top,
                    double halfWidth, int coveSteps);

/// \brief A flat \p width x \p height rectangle (two triangles) centred at \p centre whose
/// front side (the emitting side of an area light) faces \p target; the \p width side is
/// horizontal (along x for a panel facing straight down).
void buildPanel(MeshBuilder &m, V3 centre, V3 target, double width, double height);

} // namespace mkscene
