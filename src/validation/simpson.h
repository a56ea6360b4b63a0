/// \file simpson.h
/// \brief Adaptive Simpson quadrature in one and two dimensions (for expected histogram counts).
#pragma once

#include <functional>

namespace nori {

/// \brief Integral of \p f over [a, b] by adaptive Simpson's rule: an interval is split until
/// its two halves agree with the whole to 15 * eps (Lyness 1969), with Richardson's correction
/// added, or \p maxDepth levels are used.
double adaptiveSimpson(const std::function<double(double)> &f, double a, double b, double eps = 1e-6,
                       int maxDepth = 6);

/// \brief Integral of \p f over [x0, x1] x [y0, y1]: adaptiveSimpson in x of adaptiveSimpson in y.
double adaptiveSimpson2D(const std::function<double(double, double)> &f, double x0, double y0, double x1, double y1,
                         double eps = 1e-6, int maxDepth = 6);

/// \brief adaptiveSimpson2D over the open cell (x0, x1) x (y0, y1): the edges move inward by
/// 1e-7 of the cell's size, so a density that jumps on an edge (a hemisphere's horizon, a
/// triangle's side) is sampled from inside the cell only. The area left out is negligible.
double integrateCell(const std::function<double(double, double)> &f, double x0, double y0, double x1, double y1);

} // namespace nori
