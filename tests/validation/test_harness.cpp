/// \file test_harness.cpp
/// \brief The <test> objects through the parser: file checks with located messages, and runs
/// that pass for correct estimators and fail for deliberately wrong ones (test-only BSDFs).
#include <error_of.h>
#include <gtest/gtest.h>
#include <nori/bsdf.h>
#include <nori/frame.h>
#include <nori/parser.h>
#include <nori/statistical_test.h>
#include <nori/warp.h>
#include <temp_dir.h>

using namespace nori;

namespace {

/// Test-only BSDF: cosine-weighted samples, but a pdf() that claims they are uniform over the
/// hemisphere. eval is consistent with pdf, so sample() weights still average right.
class WrongPdfBSDF : public BSDF {
public:
    explicit WrongPdfBSDF(const PropertyList &) {}
    Color3f eval(const BSDFQueryRecord &rec) const override {
        return Color3f(pdf(rec) > 0.0f ? 0.5f * InvPi : 0.0f);
    }
    float pdf(const BSDFQueryRecord &rec) const override {
        if (rec.measure != EMeasure::SolidAngle || rec.wi.z() <= 0.0f || rec.wo.z() <= 0.0f) return 0.0f;
        return InvTwoPi;
    }
    Color3f sample(BSDFQueryRecord &rec, const Point2f &u) const override {
        if (rec.wi.z() <= 0.0f) return Color3f(0.0f);
        rec.wo = squareToCosineHemisphere(u);
        rec.measure = EMeasure::SolidAngle;
        return Color3f(0.5f);
    }
    std::string toString() const override { return "WrongPdfBSDF[]"; }
};
NORI_REGISTER_CLASS(WrongPdfBSDF, "test_wrong_pdf", EBSDF);

/// Test-only BSDF: a diffuse BSDF whose sample() weight is biased 1% high (albedo 0.5 claimed).
class BiasedWeightBSDF : public BSDF {
public:
    explicit BiasedWeightBSDF(const PropertyList &) {}
    Color3f eval(const BSDFQueryRecord &rec) const override {
        return Color3f(rec.wi.z() > 0.0f && rec.wo.z() > 0.0f ? 0.5f * InvPi : 0.0f);
    }
    float pdf(const BSDFQueryRecord &rec) const override {
        return rec.wi.z() > 0.0f && rec.wo.z() > 0.0f ? rec.wo.z() * InvPi : 0.0f;
    }
    Color3f sample(BSDFQueryRecord &rec, const Point2f &u) const override {
        if (rec.wi.z() <= 0.0f) return Color3f(0.0f);
        rec.wo = squareToCosineHemisphere(u);
        rec.measure = EMeasure::SolidAngle;
        // Noise like a real estimator, mean 0.505 instead of 0.5.
        return Color3f(0.505f * 2.0f * u.x());
    }
    std::string toString() const override { return "BiasedWeightBSDF[]"; }
};
NORI_REGISTER_CLASS(BiasedWeightBSDF, "test_biased_weight", EBSDF);

struct Outcome {
    bool passed;
    std::string report;
};

Outcome runTestFile(const std::string &xml) {
    TempDir dir;
    std::unique_ptr<NoriObject> root = loadFromXML(dir.write("test.xml", xml));
    auto *test = dynamic_cast<StatisticalTest *>(root.get());
    if (!test) throw std::runtime_error("root is not a test");
    std::FILE *out = std::tmpfile();
    bool passed = test->run(out);
    std::rewind(out);
    std::string report;
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, out)) > 0;) report.append(buffer, n);
    std::fclose(out);
    return {passed, report};
}

/// The message of loading \p xml, which must fail; "FILE:LINE" is checked for \p line.
std::string loadErrorAt(const std::string &xml, int line) {
    TempDir dir;
    std::string path = dir.write("bad.xml", xml);
    std::string message = errorOf([&] { loadFromXML(path); });
    EXPECT_EQ(message.rfind(path + ":" + std::to_string(line) + ":", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
}

size_t count(const std::string &text, const std::string &what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

} // namespace

TEST(Chi2TestHarness, PassesDiffuseAndRejectsAWrongPdf) {
    Outcome good = runTestFile("<test type=\"chi2test\"><integer name=\"testCount\" value=\"2\"/>"
                               "<integer name=\"sampleCount\" value=\"200000\"/><bsdf type=\"diffuse\"/></test>");
    EXPECT_TRUE(good.passed) << good.report;
    EXPECT_NE(good.report.find("Passed 2/2 tests."), std::string::npos) << good.report;
    EXPECT_NE(good.report.find("Accumulating 200000 samples into a 10x20 contingency table"), std::string::npos);

    Outcome bad = runTestFile("<test type=\"chi2test\"><integer name=\"testCount\" value=\"2\"/>"
                              "<integer name=\"sampleCount\" value=\"200000\"/><bsdf type=\"test_wrong_pdf\"/></test>");
    EXPECT_FALSE(bad.passed) << bad.report;
    EXPECT_EQ(count(bad.report, "***** Rejected *****"), 2u) << bad.report;
    EXPECT_NE(bad.report.find("Passed 0/2 tests."), std::string::npos) << bad.report;
}

TEST(TTestHarness, PassesDiffuseAndRejectsABiasedWeight) {
    const std::string angles = "<string name=\"angles\" value=\"0, 50\"/><string name=\"references\" value=\"0.5, 0.5\"/>";
    Outcome good = runTestFile("<test type=\"ttest\">" + angles + "<bsdf type=\"diffuse\"/></test>");
    EXPECT_TRUE(good.passed) << good.report;
    EXPECT_NE(good.report.find("Testing (angle=50): Diffuse"), std::string::npos) << good.report;
    Outcome bad = runTestFile("<test type=\"ttest\">" + angles + "<bsdf type=\"test_biased_weight\"/></test>");
    EXPECT_FALSE(bad.passed) << bad.report;
    EXPECT_EQ(count(bad.report, "***** Rejected *****"), 2u) << bad.report;
    // The t-test alone is blind to a wrong pdf whose weights average right (that is chi2test's job).
    Outcome blind = runTestFile("<test type=\"ttest\">" + angles + "<bsdf type=\"test_wrong_pdf\"/></test>");
    EXPECT_TRUE(blind.passed) << blind.report;
}

TEST(TestFiles, MismatchedReferenceCountsAreLocated) {
    std::string m = loadErrorAt("<test type=\"ttest\">\n<string name=\"angles\" value=\"0, 30, 60\"/>\n"
                                "<string name=\"references\" value=\"1, 1\"/>\n<bsdf type=\"mirror\"/>\n</test>",
                                3);
    EXPECT_NE(m.find("2 reference values for 3 angles x 1 BSDFs (expected 3)"), std::string::npos) << m;
    m = loadErrorAt("<test type=\"ttest\">\n<string name=\"references\" value=\"1\"/>\n"
                    "<bsdf type=\"diffuse\"/>\n</test>",
                    1);
    EXPECT_NE(m.find("a BSDF ttest needs the incident angles"), std::string::npos) << m;
}

TEST(TestFiles, BadListsChildrenAndParameters) {
    EXPECT_NE(loadErrorAt("<test type=\"ttest\">\n<string name=\"angles\" value=\"0, x5\"/>\n"
                          "<string name=\"references\" value=\"1, 1\"/><bsdf type=\"mirror\"/></test>",
                          2)
                  .find("'x5' in the angles list is not a finite number"),
              std::string::npos);
    EXPECT_NE(loadErrorAt("<test type=\"chi2test\">\n<integrator type=\"normals\"/>\n</test>", 2)
                  .find("a chi2test tests <bsdf> elements, not a <integrator>"),
              std::string::npos);
    EXPECT_NE(loadErrorAt("<test type=\"chi2test\">\n</test>", 1).find("needs <bsdf> elements"), std::string::npos);
    EXPECT_NE(loadErrorAt("<test type=\"chi2test\">\n<integer name=\"resolution\" value=\"1\"/>\n"
                          "<bsdf type=\"diffuse\"/></test>",
                          2)
                  .find("resolution must be in [2, 1000], got 1"),
              std::string::npos);
    EXPECT_NE(loadErrorAt("<test type=\"ttest\">\n<float name=\"significanceLevel\" value=\"1.5\"/>\n"
                          "<bsdf type=\"diffuse\"/></test>",
                          2)
                  .find("significanceLevel must be in (0, 1)"),
              std::string::npos);
    EXPECT_NE(loadErrorAt("<test type=\"anova\">\n</test>", 1).find("unknown test type 'anova'"), std::string::npos);
}
