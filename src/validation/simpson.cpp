/// \file simpson.cpp
/// \brief Adaptive Simpson quadrature (Kuncir 1962; stopping rule of Lyness 1969).
#include "simpson.h"
#include <cmath>

namespace nori {

namespace {
/// One level of refinement of [a, b] whose Simpson estimate is \p whole (fa, fm, fb known).
double refine(const std::function<double(double)> &f, double a, double b, double fa, double fm, double fb,
              double whole, double eps, int depth) {
    const double m = 0.5 * (a + b);
    const double flm = f(0.5 * (a + m)), frm = f(0.5 * (m + b));
    const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const double delta = left + right - whole;
    if (depth <= 0 || std::abs(delta) <= 15.0 * eps) return left + right + delta / 15.0;
    return refine(f, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
           refine(f, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}
} // namespace

double adaptiveSimpson(const std::function<double(double)> &f, double a, double b, double eps, int maxDepth) {
    const double fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
    const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    return refine(f, a, b, fa, fm, fb, whole, eps, maxDepth);
}

double adaptiveSimpson2D(const std::function<double(double, double)> &f, double x0, double y0, double x1, double y1,
                         double eps, int maxDepth) {
    auto inner = [&](double x) {
        return adaptiveSimpson([&](double y) { return f(x, y); }, y0, y1, eps, maxDepth);
    };
    return adaptiveSimpson(inner, x0, x1, eps, maxDepth);
}

double integrateCell(const std::function<double(double, double)> &f, double x0, double y0, double x1, double y1) {
    const double dx = 1e-7 * (x1 - x0), dy = 1e-7 * (y1 - y0);
    // Scale back to the full cell: the shrunken one is smaller by (1 - 2e-7)^2.
    const double scale = (x1 - x0) * (y1 - y0) / ((x1 - x0 - 2 * dx) * (y1 - y0 - 2 * dy));
    return scale * adaptiveSimpson2D(f, x0 + dx, y0 + dy, x1 - dx, y1 - dy);
}

} // namespace nori
