/// \file exact_edges.h
/// \brief The exact hit decision of a ray and a triangle given in float: the signs of the three
/// edge volumes d . ((p_j - o) x (p_k - o)), computed without rounding errors.
///
/// The watertight kernel decides most lanes with float edge functions whose rounding error it
/// bounds; the lanes within that bound of an edge come here (rare: rays within ~1e-6 of an edge,
/// relative to the problem's scale). The real ray and the real triangle decide, so the answer is
/// watertight (the two triangles of a shared edge see the same volume with opposite signs) and
/// independent of the order of operations: every width, every accelerator, every machine.
#pragma once

namespace nori {

/// \brief Edge volumes of the ray (o, d) and the triangle (p[0], p[1], p[2]) (rows x, y, z):
/// vol[0] = d . ((p1 - o) x (p2 - o)) (the weight of p0), vol[1] = d . ((p2 - o) x (p0 - o)),
/// vol[2] = d . ((p0 - o) x (p1 - o)). Each has its exact sign (0 only when the exact value is
/// 0) and a value within a relative 2^-40 of the exact one where that sign comes from the double
/// evaluation (its rounding error bounded), else the sign alone (+-1 or 0). The ray crosses the
/// triangle's plane inside the closed triangle exactly when the signs are not mixed and not all
/// zero. Returns false when an input is not finite (no decision: a miss).
bool exactEdgeVolumes(const float o[3], const float d[3], const float p[3][3], double vol[3]);

/// \brief Whether the finite corners p[0], p[1], p[2] lie on one line (two or three of them
/// coinciding included), decided exactly: the normal (p1 - p0) x (p2 - p0) is zero. No ray
/// crosses such a triangle inside: its three edge volumes sum to d . n = 0 for every ray, so
/// their signs are mixed or all zero.
bool exactlyCollinear(const float p[3][3]);

} // namespace nori
