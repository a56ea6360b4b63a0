/// \file statistical_test.h
/// \brief Root object of a Nori test file (`<test type="ttest">`, `<test type="chi2test">`):
/// `nori FILE.xml` runs it instead of rendering.
#pragma once

#include <nori/object.h>
#include <cstdio>

namespace nori {

/// \brief A statistical test of estimators (BSDFs, scenes) against references or densities.
/// The parser builds and checks it (bad files fail with FILE:LINE messages); run() does the work.
class StatisticalTest : public NoriObject {
public:
    /// \brief Run every test, writing a per-test report and the summary line "Passed P/T tests."
    /// to \p out. True when every test passed.
    virtual bool run(std::FILE *out) const = 0;

    EClassType getClassType() const override { return ETest; }
};

} // namespace nori
