/// \file fresnel.h
/// \brief Fresnel reflectance of a smooth dielectric interface, and the directions it pairs with.
#pragma once

#include <nori/common.h>

namespace nori {

/// \brief Unpolarised Fresnel reflectance for light arriving with cosine \p cosThetaI to the
/// normal of an interface between \p extIOR (the side the normal points into) and \p intIOR.
/// A negative \p cosThetaI means the light comes from the inside. Returns 1 under total
/// internal reflection and 0 when the two indices are equal (no interface).
float fresnelDielectric(float cosThetaI, float extIOR, float intIOR);

/// \brief Mirror \p v about the local normal (0, 0, 1).
inline Vector3f reflectLocal(const Vector3f &v) { return Vector3f(-v.x(), -v.y(), v.z()); }

/// \brief Refract \p wi (pointing away from the surface, local frame) through the interface of
/// relative index \p eta = eta_wi_side / eta_other_side. Returns false under total internal
/// reflection; otherwise \p wt points into the other side (its z has the opposite sign of wi.z).
bool refractLocal(const Vector3f &wi, float eta, Vector3f &wt);

} // namespace nori
