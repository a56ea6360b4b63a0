/// \file bsdf_util.h
/// \brief Helpers shared by the BSDF tests: creating a BSDF by name, directions by angle.
#pragma once

#include <nori/bsdf.h>
#include <pcg_random.hpp>

namespace nori::test {

/// \brief A BSDF of type \p type built from \p props, as the parser would build it.
inline std::unique_ptr<BSDF> makeBSDF(const std::string &type, PropertyList props = {}) {
    props.setLocation("test.xml:1");
    std::unique_ptr<NoriObject> object = NoriObjectFactory::createInstance(NoriObject::EBSDF, type, props);
    object->activate();
    return std::unique_ptr<BSDF>(static_cast<BSDF *>(object.release()));
}

/// \brief Unit direction at polar angle \p thetaDeg and azimuth \p phiDeg (local frame).
inline Vector3f direction(float thetaDeg, float phiDeg = 0.0f) {
    float t = degToRad(thetaDeg), p = degToRad(phiDeg);
    return Vector3f(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

/// \brief Uniform floats in [0, 1) from a fixed-seed PCG32 (tests are reproducible).
class Uniform {
public:
    explicit Uniform(uint64_t stream = 1) : m_rng(0x853c49e6748fea9bULL, stream) {}
    float next() { return float(m_rng() >> 8) * 0x1p-24f; }
    Point2f next2D() {
        float x = next();
        return Point2f(x, next());
    }

private:
    pcg32 m_rng;
};

} // namespace nori::test
