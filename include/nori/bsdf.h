/// \file bsdf.h
/// \brief Surface scattering model interface.
#pragma once

#include <nori/color.h>
#include <nori/object.h>

namespace nori {

/// \brief A BSDF evaluated in the local shading frame (z = normal).
class BSDF : public NoriObject {
public:
    /// \brief BSDF value for incident \p wi and outgoing \p wo (both local, unit length).
    virtual Color3f eval(const Vector3f &wi, const Vector3f &wo) const = 0;
    EClassType getClassType() const override { return EBSDF; }
};

} // namespace nori
