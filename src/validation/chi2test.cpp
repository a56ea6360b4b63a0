/// \file chi2test.cpp
/// \brief Nori's `<test type="chi2test">`: does a BSDF's sample() draw directions with the
/// density its pdf() claims? Pearson's chi^2 test on a histogram over the sphere.
#include "hypothesis.h"
#include "simpson.h"
#include <nori/bsdf.h>
#include <nori/statistical_test.h>
#include <pcg_random.hpp>
#include <tbb/parallel_for.h>

namespace nori {

/// \brief For each BSDF, \c testCount random incident directions; for each, \c sampleCount
/// sampled directions binned over (cos theta, phi) in resolution x 2 resolution cells of equal
/// solid angle, against sampleCount times the pdf integrated over each cell.
class ChiSquareTest : public StatisticalTest {
public:
    explicit ChiSquareTest(const PropertyList &props) {
        m_significanceLevel = props.getFloat("significanceLevel", 0.01f);
        if (!(m_significanceLevel > 0.0 && m_significanceLevel < 1.0))
            props.fail("significanceLevel", fmt::format("significanceLevel must be in (0, 1), got {}",
                                                        m_significanceLevel));
        m_resolution = props.getInteger("resolution", 10);
        if (m_resolution < 2 || m_resolution > 1000)
            props.fail("resolution", fmt::format("resolution must be in [2, 1000], got {}", m_resolution));
        m_minExpFrequency = props.getInteger("minExpFrequency", 5);
        if (m_minExpFrequency < 1)
            props.fail("minExpFrequency", fmt::format("minExpFrequency must be at least 1, got {}", m_minExpFrequency));
        // -1 (Nori's default): 5000 samples per cell.
        const int sampleCount = props.getInteger("sampleCount", -1);
        if (sampleCount != -1 && (sampleCount < 1 || sampleCount > (1 << 30)))
            props.fail("sampleCount", fmt::format("sampleCount must be -1 (automatic) or in [1, {}], got {}",
                                                  1 << 30, sampleCount));
        m_sampleCount = sampleCount == -1 ? uint64_t(m_resolution) * 2 * m_resolution * 5000 : uint64_t(sampleCount);
        m_testCount = props.getInteger("testCount", 5);
        if (m_testCount < 1 || m_testCount > 1000)
            props.fail("testCount", fmt::format("testCount must be in [1, 1000], got {}", m_testCount));
    }

    void addChild(std::unique_ptr<NoriObject> child) override {
        if (child->getClassType() != EBSDF)
            throw NoriException("{}: a chi2test tests <bsdf> elements, not a <{}>", child->location(),
                                classTypeName(child->getClassType()));
        m_bsdfs.emplace_back(static_cast<BSDF *>(child.release()));
    }

    void activate() override {
        if (m_bsdfs.empty()) throw NoriException("{}: a chi2test needs <bsdf> elements to test", location());
    }

    bool run(std::FILE *out) const override {
        const double level = sidakCorrection(m_significanceLevel, m_testCount * int(m_bsdfs.size()));
        pcg32 rng;  // one fixed-seed stream for the whole file
        auto uniform = [&rng] { return float(rng() >> 8) * 0x1p-24f; };
        int passed = 0, total = 0;
        for (const auto &bsdf : m_bsdfs)
            for (int test = 0; test < m_testCount; ++test) {
                // Incident direction uniform in cos(theta) over the upper hemisphere.
                const float cosTheta = uniform(), phi = 2.0f * Pi * uniform();
                const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
                const Vector3f wi(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
                std::fprintf(out, "%s\nTesting: %s\nIncident direction (%.6g, %.6g, %.6g)\n", kRule,
                             bsdf->toString().c_str(), wi.x(), wi.y(), wi.z());
                std::fprintf(out, "Accumulating %llu samples into a %dx%d contingency table .. ",
                             (unsigned long long)m_sampleCount, m_resolution, 2 * m_resolution);
                std::fflush(out);
                std::string problem;
                std::vector<double> observed = histogram(*bsdf, wi, uniform, problem);
                std::fputs("done.\nIntegrating expected frequencies .. ", out);
                std::fflush(out);
                std::vector<double> expected = expectedCounts(*bsdf, wi);
                std::fputs("done.\n", out);
                HypothesisResult result;
                if (problem.empty()) {
                    result = chi2Test(observed, expected, double(m_sampleCount), m_minExpFrequency, level);
                } else {
                    result.report = problem + " Rejecting the null hypothesis!\n";
                }
                std::fputs(result.report.c_str(), out);
                passed += result.accepted;
                ++total;
            }
        std::fprintf(out, "%s\nPassed %d/%d tests.\n", kRule, passed, total);
        return passed == total;
    }

    std::string toString() const override {
        return fmt::format("ChiSquareTest[significanceLevel={}, resolution={}, minExpFrequency={}, sampleCount={}, "
                           "testCount={}]",
                           m_significanceLevel, m_resolution, m_minExpFrequency, m_sampleCount, m_testCount);
    }

private:
    static constexpr const char *kRule = "------------------------------------------------------";

    int phiBins() const { return 2 * m_resolution; }

    /// Counts of sampled directions per cell; failed samples (weight 0) are left out. A sample
    /// no density can describe (a discrete direction, a weight that is not a finite
    /// non-negative number) is reported in \p problem.
    template <typename Uniform>
    std::vector<double> histogram(const BSDF &bsdf, const Vector3f &wi, Uniform &uniform, std::string &problem) const {
        std::vector<double> counts(size_t(m_resolution) * phiBins(), 0.0);
        uint64_t discrete = 0, invalid = 0;
        for (uint64_t i = 0; i < m_sampleCount; ++i) {
            BSDFQueryRecord rec(wi);
            const float u = uniform();
            const Color3f weight = bsdf.sample(rec, Point2f(u, uniform()));
            if (!isFinite(weight) || (weight < 0.0f).any()) {
                ++invalid;
                continue;
            }
            if ((weight == 0.0f).all()) continue;
            if (rec.measure == EMeasure::Discrete) {
                ++discrete;
                continue;
            }
            const int zBin = clamp(int(std::floor((rec.wo.z() * 0.5f + 0.5f) * m_resolution)), 0, m_resolution - 1);
            float phi = std::atan2(rec.wo.y(), rec.wo.x());
            if (phi < 0.0f) phi += 2.0f * Pi;
            const int phiBin = clamp(int(std::floor(phi * InvTwoPi * phiBins())), 0, phiBins() - 1);
            counts[size_t(zBin) * phiBins() + phiBin] += 1.0;
        }
        if (discrete > 0)
            problem = fmt::format("{} samples were discrete (specular) directions, which have no density: a chi2test "
                                  "applies to smooth BSDFs.", discrete);
        else if (invalid > 0)
            problem = fmt::format("{} samples had a negative or non-finite weight.", invalid);
        return counts;
    }

    /// sampleCount x the integral of pdf over each cell; solid angle is d(cos theta) d(phi), so
    /// the cell integral needs no Jacobian. Cells are independent: integrated in parallel.
    std::vector<double> expectedCounts(const BSDF &bsdf, const Vector3f &wi) const {
        std::vector<double> expected(size_t(m_resolution) * phiBins(), 0.0);
        // Edges from integers: the horizon z = 0 (where every pdf here jumps to zero) must be an
        // exact cell edge, integrated from inside each cell, or Simpson's rule samples the upper
        // lobe from the cell below it.
        auto zEdge = [this](int k) { return double(2 * k - m_resolution) / m_resolution; };
        auto phiEdge = [this](int k) { return 2.0 * M_PI * k / phiBins(); };
        auto density = [&](double z, double phi) {
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            const Vector3f wo(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
            return double(bsdf.pdf(BSDFQueryRecord(wi, wo, EMeasure::SolidAngle)));
        };
        tbb::parallel_for(size_t(0), expected.size(), [&](size_t cell) {
            const int zBin = int(cell / phiBins()), phiBin = int(cell % phiBins());
            expected[cell] = double(m_sampleCount) * integrateCell(density, zEdge(zBin), phiEdge(phiBin),
                                                                       zEdge(zBin + 1), phiEdge(phiBin + 1));
        });
        return expected;
    }

    double m_significanceLevel;
    int m_resolution, m_minExpFrequency, m_testCount;
    uint64_t m_sampleCount;
    std::vector<std::unique_ptr<BSDF>> m_bsdfs;
};

NORI_REGISTER_CLASS(ChiSquareTest, "chi2test", ETest);

} // namespace nori
