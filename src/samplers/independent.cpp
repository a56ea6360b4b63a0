/// \file independent.cpp
/// \brief Independent uniform sampler on a PCG32 generator (O'Neill 2014).
#include <nori/sampler.h>
#include <pcg_random.hpp>

namespace nori {

class IndependentSampler : public Sampler {
public:
    explicit IndependentSampler(const PropertyList &props) {
        m_sampleCount = props.getInteger("sampleCount", 1);
        // 2^20 samples per pixel is far beyond anything sensible and guards against typos.
        if (m_sampleCount <= 0 || m_sampleCount > (1 << 20))
            props.fail("sampleCount", fmt::format("sampleCount must be in [1, {}], got {}", 1 << 20, m_sampleCount));
    }

    std::unique_ptr<Sampler> clone() const override { return std::make_unique<IndependentSampler>(*this); }

    void prepare(uint64_t blockIndex) override { m_rng = pcg32(0x853c49e6748fea9bULL, blockIndex); }

    float next1D() override { return float(m_rng() >> 8) * 0x1p-24f; }
    Point2f next2D() override {
        float x = next1D();
        return Point2f(x, next1D());
    }

    std::string toString() const override { return fmt::format("Independent[sampleCount={}]", m_sampleCount); }

private:
    pcg32 m_rng;
};

NORI_REGISTER_CLASS(IndependentSampler, "independent", ESampler);

} // namespace nori
