/// \file rfilter.h
/// \brief Reconstruction filter interface (placeholder until the filter plugins land).
#pragma once

#include <nori/object.h>

namespace nori {

/// \brief Separable 1D reconstruction filter.
class ReconstructionFilter : public NoriObject {
public:
    float radius() const { return m_radius; }
    virtual float eval(float x) const = 0;
    EClassType getClassType() const override { return EReconstructionFilter; }

protected:
    float m_radius = 0.5f;
};

} // namespace nori
