/// \file rfilter.h
/// \brief Separable pixel reconstruction filters (gaussian, box, tent, mitchell).
#pragma once

#include <nori/object.h>

namespace nori {

/// \brief A symmetric 1D filter kernel; the 2D weight of an image sample is eval(dx) * eval(dy).
///
/// Kernels need not integrate to one: ImageBlock divides every pixel by its accumulated weight.
/// Implementations are registered as "gaussian", "box", "tent" and "mitchell".
class ReconstructionFilter : public NoriObject {
public:
    /// \brief Half-width of the support: eval(x) is zero for |x| > radius().
    float radius() const { return m_radius; }

    /// \brief Kernel value at signed distance \p x (in pixels) from a pixel centre.
    virtual float eval(float x) const = 0;

    /// \brief Always EReconstructionFilter.
    EClassType getClassType() const override { return EReconstructionFilter; }

protected:
    float m_radius = 0.5f;
};

} // namespace nori
