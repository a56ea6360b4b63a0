/// \file fresnel.cpp
/// \brief Fresnel equations for dielectrics (Hecht, "Optics", ch. 4) and Snell refraction.
#include <nori/fresnel.h>

namespace nori {

float fresnelDielectric(float cosThetaI, float extIOR, float intIOR) {
    if (extIOR == intIOR) return 0.0f;
    float etaI = extIOR, etaT = intIOR;
    if (cosThetaI < 0.0f) {  // arriving from the inside: swap the media
        std::swap(etaI, etaT);
        cosThetaI = -cosThetaI;
    }
    cosThetaI = std::min(cosThetaI, 1.0f);
    const float eta = etaI / etaT;
    const float sin2ThetaT = eta * eta * std::max(0.0f, 1.0f - cosThetaI * cosThetaI);
    if (sin2ThetaT >= 1.0f) return 1.0f;  // total internal reflection
    const float cosThetaT = std::sqrt(1.0f - sin2ThetaT);
    // Amplitude ratios for the s- and p-polarised parts; unpolarised light averages their squares.
    const float rs = (etaI * cosThetaI - etaT * cosThetaT) / (etaI * cosThetaI + etaT * cosThetaT);
    const float rp = (etaT * cosThetaI - etaI * cosThetaT) / (etaT * cosThetaI + etaI * cosThetaT);
    return 0.5f * (rs * rs + rp * rp);
}

bool refractLocal(const Vector3f &wi, float eta, Vector3f &wt) {
    const float cosThetaI = wi.z();
    const float sin2ThetaT = eta * eta * std::max(0.0f, 1.0f - cosThetaI * cosThetaI);
    if (sin2ThetaT >= 1.0f) return false;
    const float cosThetaT = std::sqrt(1.0f - sin2ThetaT);
    // Tangential part scales by eta and flips (wi points away from the surface); the normal
    // part has length cosThetaT on the far side.
    wt = Vector3f(-eta * wi.x(), -eta * wi.y(), cosThetaI >= 0.0f ? -cosThetaT : cosThetaT);
    return true;
}

} // namespace nori
