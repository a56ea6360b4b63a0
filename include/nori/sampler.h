/// \file sampler.h
/// \brief Sample generator interface.
#pragma once

#include <nori/object.h>

namespace nori {

/// \brief Produces the random numbers of one image block. Each block gets its own clone,
/// seeded from the block alone, so images do not depend on the thread count.
class Sampler : public NoriObject {
public:
    /// \brief An independent copy, to be prepare()d for one block.
    virtual std::unique_ptr<Sampler> clone() const = 0;
    /// \brief Seed deterministically for the block with index \p blockIndex.
    virtual void prepare(uint64_t blockIndex) = 0;
    /// \brief Uniform sample in [0, 1).
    virtual float next1D() = 0;
    /// \brief Uniform sample in [0, 1)^2.
    virtual Point2f next2D() = 0;
    /// \brief Samples per pixel.
    int sampleCount() const { return m_sampleCount; }

    EClassType getClassType() const override { return ESampler; }

protected:
    int m_sampleCount = 1;
};

} // namespace nori
