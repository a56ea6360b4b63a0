/// \file ttest.cpp
/// \brief Nori's `<test type="ttest">`: the mean of a BSDF's sampling weights (its directional
/// albedo) or of a scene's pixel estimates against reference values, one-sample Student t-test
/// with the Sidak correction.
#include "hypothesis.h"
#include <nori/bsdf.h>
#include <nori/scene.h>
#include <nori/statistical_test.h>
#include <charconv>
#include <nori/running_statistics.h>
#include <pcg_random.hpp>

namespace nori {

namespace {

/// Numbers separated by commas and/or whitespace (Nori's `angles` and `references`).
std::vector<double> parseNumberList(const PropertyList &props, const std::string &name) {
    const std::string text = props.getString(name, "");
    std::vector<double> values;
    size_t i = 0;
    while (i < text.size()) {
        if (text[i] == ',' || std::isspace((unsigned char)text[i])) {
            ++i;
            continue;
        }
        size_t end = text.find_first_of(", \t\r\n", i);
        if (end == std::string::npos) end = text.size();
        std::string token = text.substr(i, end - i);
        const char *first = token.data() + (token[0] == '+' ? 1 : 0);
        double value = 0.0;
        auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value))
            props.fail(name, fmt::format("'{}' in the {} list is not a finite number", token.substr(0, 60), name));
        values.push_back(value);
        i = end;
    }
    return values;
}

float uniformFloat(pcg32 &rng) { return float(rng() >> 8) * 0x1p-24f; }

} // namespace

/// \brief One-sample t-tests of BSDF albedos (BSDF mode: \c angles and references per angle)
/// or of scene pixel values (scene mode: one reference per scene).
class StudentsTTest : public StatisticalTest {
public:
    explicit StudentsTTest(const PropertyList &props) {
        m_significanceLevel = props.getFloat("significanceLevel", 0.01f);
        if (!(m_significanceLevel > 0.0 && m_significanceLevel < 1.0))
            props.fail("significanceLevel", fmt::format("significanceLevel must be in (0, 1), got {}",
                                                        m_significanceLevel));
        const int sampleCount = props.getInteger("sampleCount", 100000);
        if (sampleCount < 2 || sampleCount > (1 << 30))
            props.fail("sampleCount", fmt::format("sampleCount must be in [2, {}], got {}", 1 << 30, sampleCount));
        m_sampleCount = uint64_t(sampleCount);
        m_hasAngles = props.has("angles");
        m_angles = parseNumberList(props, "angles");
        m_references = parseNumberList(props, "references");
        m_anglesWhere = props.whereIs("angles");
        m_referencesWhere = props.whereIs("references");
    }

    void addChild(std::unique_ptr<NoriObject> child) override {
        switch (child->getClassType()) {
        case EBSDF: m_bsdfs.emplace_back(static_cast<BSDF *>(child.release())); break;
        case EScene: m_scenes.emplace_back(static_cast<Scene *>(child.release())); break;
        default:
            throw NoriException("{}: a ttest tests <bsdf> or <scene> elements, not a <{}>", child->location(),
                                classTypeName(child->getClassType()));
        }
    }

    /// Checks the file's consistency before anything runs.
    void activate() override {
        if (m_bsdfs.empty() && m_scenes.empty())
            throw NoriException("{}: a ttest needs <bsdf> or <scene> elements to test", location());
        if (!m_bsdfs.empty() && !m_scenes.empty())
            throw NoriException("{}: a ttest cannot test BSDFs and scenes at the same time", location());
        if (!m_bsdfs.empty()) {
            if (m_angles.empty())
                throw NoriException("{}: a BSDF ttest needs the incident angles (string 'angles', degrees)",
                                    m_anglesWhere);
            if (m_references.size() != m_angles.size() * m_bsdfs.size())
                throw NoriException("{}: {} reference values for {} angles x {} BSDFs (expected {})",
                                    m_referencesWhere, m_references.size(), m_angles.size(), m_bsdfs.size(),
                                    m_angles.size() * m_bsdfs.size());
        } else {
            if (m_hasAngles)
                throw NoriException("{}: 'angles' applies to BSDF ttests, not to scenes", m_anglesWhere);
            if (m_references.size() != m_scenes.size())
                throw NoriException("{}: {} reference values for {} scenes (expected one per scene)",
                                    m_referencesWhere, m_references.size(), m_scenes.size());
        }
    }

    bool run(std::FILE *out) const override {
        const double level = sidakCorrection(m_significanceLevel, int(m_references.size()));
        int passed = 0, total = 0;
        auto conclude = [&](const RunningStatistics &stats, double reference) {
            HypothesisResult result = tTest(stats.mean(), stats.variance(), stats.count(), reference, level);
            std::fputs(result.report.c_str(), out);
            passed += result.accepted;
            ++total;
        };
        if (!m_bsdfs.empty()) {
            pcg32 rng;  // one fixed-seed stream for the whole file, as Nori
            for (size_t b = 0; b < m_bsdfs.size(); ++b)
                for (size_t a = 0; a < m_angles.size(); ++a) {
                    std::fprintf(out, "%s\nTesting (angle=%g): %s\nDrawing %llu samples .. ", kRule, m_angles[a],
                                 m_bsdfs[b]->toString().c_str(), (unsigned long long)m_sampleCount);
                    std::fflush(out);
                    const float theta = degToRad(float(m_angles[a]));
                    const Vector3f wi(std::sin(theta), 0.0f, std::cos(theta));
                    RunningStatistics stats;
                    for (uint64_t i = 0; i < m_sampleCount; ++i) {
                        BSDFQueryRecord rec(wi);
                        float u = uniformFloat(rng);
                        Color3f weight = m_bsdfs[b]->sample(rec, Point2f(u, uniformFloat(rng)));
                        stats.add(luminance(weight));
                    }
                    std::fputs("done.\n", out);
                    conclude(stats, m_references[b * m_angles.size() + a]);
                }
        } else {
            for (size_t s = 0; s < m_scenes.size(); ++s) {
                const Scene &scene = *m_scenes[s];
                std::fprintf(out, "%s\nTesting scene: %s\nGenerating %llu paths .. ", kRule,
                             scene.toString().c_str(), (unsigned long long)m_sampleCount);
                std::fflush(out);
                RunningStatistics stats = pixelStatistics(scene);
                std::fputs("done.\n", out);
                conclude(stats, m_references[s]);
            }
        }
        std::fprintf(out, "%s\nPassed %d/%d tests.\n", kRule, passed, total);
        return passed == total;
    }

    std::string toString() const override {
        return fmt::format("StudentsTTest[significanceLevel={}, sampleCount={}, {} BSDFs, {} scenes]",
                           m_significanceLevel, m_sampleCount, m_bsdfs.size(), m_scenes.size());
    }

private:
    static constexpr const char *kRule = "------------------------------------------------------";

    /// Luminance of camera-weighted radiance along rays through uniform film positions (the
    /// scene's own sampler is not used: a fresh default one, as Nori).
    RunningStatistics pixelStatistics(const Scene &scene) const {
        std::unique_ptr<NoriObject> object =
            NoriObjectFactory::createInstance(ESampler, "independent", PropertyList());
        std::unique_ptr<Sampler> sampler(static_cast<Sampler *>(object.release()));
        sampler->prepare(0);
        const Camera &camera = scene.camera();
        const Vector2f size = camera.outputSize().cast<float>();
        RunningStatistics stats;
        for (uint64_t i = 0; i < m_sampleCount; ++i) {
            Point2f pixel = sampler->next2D().cwiseProduct(size);
            Ray3f ray;
            Color3f weight = camera.sampleRay(ray, pixel, sampler->next2D());
            stats.add(luminance(weight * scene.integrator().Li(scene, *sampler, ray)));
        }
        return stats;
    }

    double m_significanceLevel;
    uint64_t m_sampleCount;
    bool m_hasAngles;
    std::vector<double> m_angles, m_references;
    std::string m_anglesWhere, m_referencesWhere;
    std::vector<std::unique_ptr<BSDF>> m_bsdfs;
    std::vector<std::unique_ptr<Scene>> m_scenes;
};

NORI_REGISTER_CLASS(StudentsTTest, "ttest", ETest);

} // namespace nori
