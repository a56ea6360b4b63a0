/// \file test_lanes.cpp
/// \brief The lane operations the octree node kernels rely on (lookup8, lookup16, loadBytes, ^,
/// compressStore) give the scalar answer at every width compiled into this build, for every
/// mask of eight lanes;
/// maxAbs (the watertight kernel's error bound) is max(|a|, |b|) bit for bit on every finite,
/// infinite, zero and subnormal pair; withLane sets one lane.
// GCC 12's AVX-512 permute and widening intrinsics start from _mm512_undefined_*(), which
// -Wuninitialized reports once inlined here; the value is never read.
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <accel/lanes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

using namespace nori;

namespace {

/// All 256 masks of eight lanes, run through \p L lanes at a time as the node kernel does:
/// the lanes of each mask, in order, with entries looked up through a permutation.
template <int L>
void checkCompressedLookups() {
    using F = lanes::VFloat<L>;
    using U = lanes::VUint<L>;
    const float values[8] = {0.5f, -1.0f, 2.25f, -0.0f, 1e30f, -7.0f, 3.0f, 1e-30f};
    const uint32_t words[8] = {10, 11, 12, 13, 14, 15, 16, 0x80000000u};
    const uint32_t order[8] = {7, 6, 5, 4, 3, 2, 1, 0};
    for (uint32_t flip = 0; flip < 8; ++flip) {
        for (unsigned mask = 0; mask < 256; ++mask) {
            // Room for L lanes past the last packed one, as compressStore requires.
            float gotF[16];
            uint32_t gotU[16];
            int k = 0;
            for (int j = 0; j < 8; j += L) {
                const U idx = U::loadu(order + j) ^ U(flip);
                // A float whose lane is set where the mask's bit j + lane is set.
                float sel[L];
                for (int l = 0; l < L; ++l) sel[l] = (mask >> (j + l) & 1u) ? 1.0f : 0.0f;
                const lanes::VMask<L> m = F::loadu(sel) > F(0.5f);
                compressStore(m, lookup8(words, idx), gotU + k);
                k += compressStore(m, lookup8(values, idx), gotF + k);
            }
            int n = 0;
            for (int j = 0; j < 8; ++j) {
                if (!(mask >> j & 1u)) continue;
                const uint32_t c = order[j] ^ flip;
                ASSERT_LT(n, k) << "L=" << L << " mask=" << mask;
                EXPECT_EQ(std::memcmp(&gotF[n], &values[c], sizeof(float)), 0) << "L=" << L << " mask=" << mask;
                EXPECT_EQ(gotU[n], words[c]) << "L=" << L << " mask=" << mask;
                ++n;
            }
            ASSERT_EQ(n, k) << "L=" << L << " mask=" << mask << " flip=" << flip;
        }
    }
}

TEST(Lanes, CompressedLookupsMatchScalarOneLane) { checkCompressedLookups<1>(); }

#if NORI_LANES_AVX2
TEST(Lanes, CompressedLookupsMatchScalarEightLanes) { checkCompressedLookups<8>(); }
#endif

/// maxAbs(a, b) == max(|a|, |b|) bit for bit, at L lanes, on every pair of \p values.
template <int L>
void checkMaxAbs() {
    using F = lanes::VFloat<L>;
    const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 0x1p-149f, -0x1p-149f, 0x1p-126f, -3.4e38f, 3.4e38f,
                            Infinity, -Infinity, 1.5f, -1.5f, 7e-20f, -2e19f, 0.3f};
    const int n = int(sizeof(values) / sizeof(values[0]));
    for (int i = 0; i < n; ++i)
        for (int j0 = 0; j0 < n; j0 += L) {
            float a[L], b[L], got[L];
            for (int l = 0; l < L; ++l) a[l] = values[i], b[l] = values[(j0 + l) % n];
            maxAbs(F::loadu(a), F::loadu(b)).storeu(got);
            for (int l = 0; l < L; ++l) {
                const float want = std::max(std::fabs(a[l]), std::fabs(b[l]));
                EXPECT_EQ(std::memcmp(&got[l], &want, sizeof(float)), 0)
                    << "L=" << L << ": maxAbs(" << a[l] << ", " << b[l] << ") = " << got[l] << ", want " << want;
            }
        }
}

TEST(Lanes, MaxAbsIsTheLargerMagnitudeOneLane) { checkMaxAbs<1>(); }

#if NORI_LANES_AVX2
TEST(Lanes, MaxAbsIsTheLargerMagnitudeEightLanes) { checkMaxAbs<8>(); }
#endif

#if NORI_LANES_AVX512
TEST(Lanes, MaxAbsIsTheLargerMagnitudeSixteenLanes) { checkMaxAbs<16>(); }
#endif

} // namespace

/// lookup16 through indices widened by loadBytes (the wide node kernel's order tables) gives
/// table[idx] for every lane, at L lanes, for many permutations of sixteen entries.
template <int L>
void checkLookup16() {
    using U = lanes::VUint<L>;
    float values[16];
    uint32_t words[16];
    for (int s = 0; s < 16; ++s) {
        values[s] = float(s) * 1.5f - 7.0f;
        words[s] = 0x80000000u | uint32_t(100 + s);
    }
    uint8_t order[16];
    for (int p = 0; p < 64; ++p) {
        for (int j = 0; j < 16; ++j) order[j] = uint8_t((j * 5 + p * 3 + (j >> 2) * p) % 16);
        // (Not always a permutation: lookups may repeat an entry.)
        for (int j = 0; j < 16; j += L) {
            const U idx = U::loadBytes(order + j);
            float gotF[16];
            uint32_t gotU[16];
            lookup16(values, idx).storeu(gotF);
            lookup16(words, idx).storeu(gotU);
            for (int l = 0; l < L; ++l) {
                EXPECT_EQ(gotF[l], values[order[j + l]]) << "L=" << L << " p=" << p << " lane " << j + l;
                EXPECT_EQ(gotU[l], words[order[j + l]]) << "L=" << L << " p=" << p << " lane " << j + l;
            }
        }
    }
}

TEST(Lanes, Lookup16MatchesScalarOneLane) { checkLookup16<1>(); }

#if NORI_LANES_AVX2
TEST(Lanes, Lookup16MatchesScalarEightLanes) { checkLookup16<8>(); }
#endif

#if NORI_LANES_AVX512
TEST(Lanes, Lookup16MatchesScalarSixteenLanes) { checkLookup16<16>(); }
#endif

/// withLane(f, j, x) changes lane j to x, bit for bit (a NaN too), and no other lane.
template <int L>
void checkWithLane() {
    using F = lanes::VFloat<L>;
    float base[L];
    for (int l = 0; l < L; ++l) base[l] = float(l) * 0.25f - 1.0f;
    const float xs[] = {5.0f, -0.0f, std::numeric_limits<float>::quiet_NaN(), 0x1p-149f};
    for (int j = 0; j < L; ++j)
        for (float x : xs) {
            float got[L];
            withLane(F::loadu(base), j, x).storeu(got);
            for (int l = 0; l < L; ++l) {
                const float want = l == j ? x : base[l];
                EXPECT_EQ(std::memcmp(&got[l], &want, sizeof(float)), 0) << "L=" << L << " j=" << j << " lane " << l;
            }
        }
}

TEST(Lanes, WithLaneSetsOneLaneOneLane) { checkWithLane<1>(); }

#if NORI_LANES_AVX2
TEST(Lanes, WithLaneSetsOneLaneEightLanes) { checkWithLane<8>(); }
#endif

#if NORI_LANES_AVX512
TEST(Lanes, WithLaneSetsOneLaneSixteenLanes) { checkWithLane<16>(); }
#endif

namespace {
/// firstN(n) sets lanes 0 .. n - 1, all of them from n = L on, up to the largest count its
/// contract allows (2^31 - 1), at L lanes.
template <int L>
void checkFirstN() {
    const uint32_t all = (1u << L) - 1u;
    for (uint32_t n : {0u, 1u, 2u, 3u, 5u, 7u, 8u, 9u, 15u, 16u, 17u, 100u, 65536u, 0x7fffffffu}) {
        const unsigned want = n >= uint32_t(L) ? all : (1u << n) - 1u;
        EXPECT_EQ(bits(lanes::VMask<L>::firstN(n)), want) << "L=" << L << " n=" << n;
    }
}
} // namespace

TEST(Lanes, FirstNSetsTheFirstLanesOneLane) { checkFirstN<1>(); }

#if NORI_LANES_AVX2
TEST(Lanes, FirstNSetsTheFirstLanesEightLanes) { checkFirstN<8>(); }
#endif

#if NORI_LANES_AVX512
TEST(Lanes, FirstNSetsTheFirstLanesSixteenLanes) { checkFirstN<16>(); }
#endif
