/// \file dpdf.cpp
/// \brief Discrete distribution: CDF construction and inversion.
#include <nori/dpdf.h>
#include <algorithm>

namespace nori {

void DiscretePDF::clear() {
    m_cdf.assign(1, 0.0);
    m_sum = 0.0f;
}

void DiscretePDF::append(float weight) { m_cdf.push_back(m_cdf.back() + double(std::max(weight, 0.0f))); }

float DiscretePDF::normalize() {
    double total = m_cdf.back();
    m_sum = float(total);
    if (!(total > 0.0)) return 0.0f;
    for (double &c : m_cdf) c /= total;
    m_cdf.back() = 1.0;
    return m_sum;
}

size_t DiscretePDF::sample(float u) const {
    // The first entry whose upper CDF bound exceeds u; entries of zero weight are never chosen.
    auto it = std::upper_bound(m_cdf.begin() + 1, m_cdf.end(), double(u));
    size_t i = size_t(it - m_cdf.begin()) - 1;
    return std::min(i, size() - 1);
}

size_t DiscretePDF::sampleReuse(float &u) const {
    size_t i = sample(u);
    double width = m_cdf[i + 1] - m_cdf[i];
    double t = width > 0.0 ? (double(u) - m_cdf[i]) / width : 0.0;
    // Rounding may land a hair outside [0, 1).
    u = float(std::clamp(t, 0.0, double(0x1.fffffep-1f)));
    return i;
}

} // namespace nori
