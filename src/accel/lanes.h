/// \file lanes.h
/// \brief Lanes<L>: L float lanes and their masks (L = 16 with AVX-512, 8 with AVX2 or
/// AVX-512, 1 everywhere), the small vector type the ray/triangle kernels are written over once.
///
/// In the spirit of Embree's vfloat/vbool wrappers: a kernel written as a template over L runs
/// with 16, 8 or 1 lanes, and because every lane performs the same IEEE operations in the same
/// order, all widths give bit-identical results — provided the translation unit is compiled
/// with `-ffp-contract=off` (src/accel/CMakeLists.txt), since GCC and clang both fuse a*b + c
/// into an FMA by default, also for these intrinsics.
///
/// API (F = VFloat<L>, M = VMask<L>, U = VUint<L>):
///   - F(x) broadcasts; F::loadu(p) reads L floats; F::load(p, m) reads the lanes of m and sets
///     the others to 0 without touching their memory; f.storeu(p) writes L floats;
///   - f + g, f - g, f * g, f / g (IEEE, lane by lane);
///   - f < g, <=, >, >=, == (ordered: false on NaN) and f != g (unordered: true on NaN) give M;
///   - abs(f) clears the sign bit (also of a NaN); maxAbs(f, g) = max(|f|, |g|) (one AVX-512
///     vrangeps): where f or g is a NaN the result may be a NaN or not, depending on the width;
///     use it only where a NaN argument cannot change what is decided;
///   - max(f, g) = f > g ? f : g and min(f, g) = f < g ? f : g lane by lane (the x86 maxps/minps
///     rule: the second operand on NaN or equality, so a NaN in f never wins);
///   - select(m, f, g), reduceMin(m, f) (+inf when m is empty), lane(f, j); withLane(f, j, x)
///     is f with lane j set to x (in registers: scalar stores then a vector load of the same
///     bytes would stall on store forwarding);
///   - masks: m & n, m | n, ~m (within the L lanes), any(m), bits(m) (bit j = lane j),
///     M::firstN(n) (lanes 0 .. n-1; all when n >= L; n < 2^31);
///   - U: U(x), U::loadu(p), u.storeu(p), u ^ v, lane(u, j); permute(f or u, idx) (lane j gets
///     lane idx[j]); lookup8(table, idx) (L = 1, 8: lane j gets table[idx[j]] from an 8-entry
///     float or uint32 table, idx[j] < 8); lookup16 the same from a 16-entry table (L = 1, 8, 16);
///     U::loadBytes(p) widens L bytes; bitsAt(word, idx): bit j = bit idx[j] of word (idx[j] < 32);
///     compressStore(m, f or u, dst): the lanes of m packed
///     in lane order at dst, returns their count (dst must have room for L values: lanes past
///     the count are scratch); compressStoreBits(bits, f or u, dst) the same with the lanes given
///     as a bit mask (bit j = lane j), for a mask already edited in a general register.
#pragma once

#include <nori/common.h>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#include <immintrin.h>
#define NORI_LANES_AVX512 1
#endif
#if defined(__AVX2__)
#include <immintrin.h>
#define NORI_LANES_AVX2 1
#endif

namespace nori::lanes {

/// Widest lane count of this build: what the kernels use; narrower widths exist for testing.
#if NORI_LANES_AVX512
constexpr int kMaxLanes = 16;
#elif NORI_LANES_AVX2
constexpr int kMaxLanes = 8;
#else
constexpr int kMaxLanes = 1;
#endif

template <int L> struct VMask;
template <int L> struct VFloat;
template <int L> struct VUint;

// ---------------------------------------------------------------------------------------------
// One lane: plain scalars (the reference width, and the only one without SIMD).

template <> struct VMask<1> {
    bool b;
    static VMask firstN(uint32_t n) { return {n > 0}; }
    friend VMask operator&(VMask x, VMask y) { return {x.b && y.b}; }
    friend VMask operator|(VMask x, VMask y) { return {x.b || y.b}; }
    friend VMask operator~(VMask x) { return {!x.b}; }
    friend bool any(VMask x) { return x.b; }
    friend unsigned bits(VMask x) { return x.b ? 1u : 0u; }
};

template <> struct VFloat<1> {
    float f;
    VFloat() = default;
    VFloat(float x) : f(x) {}
    static VFloat loadu(const float *p) { return *p; }
    static VFloat load(const float *p, VMask<1> m) { return m.b ? *p : 0.0f; }
    void storeu(float *p) const { *p = f; }
    friend VFloat operator+(VFloat a, VFloat b) { return a.f + b.f; }
    friend VFloat operator-(VFloat a, VFloat b) { return a.f - b.f; }
    friend VFloat operator*(VFloat a, VFloat b) { return a.f * b.f; }
    friend VFloat operator/(VFloat a, VFloat b) { return a.f / b.f; }
    friend VMask<1> operator<(VFloat a, VFloat b) { return {a.f < b.f}; }
    friend VMask<1> operator<=(VFloat a, VFloat b) { return {a.f <= b.f}; }
    friend VMask<1> operator>(VFloat a, VFloat b) { return {a.f > b.f}; }
    friend VMask<1> operator>=(VFloat a, VFloat b) { return {a.f >= b.f}; }
    friend VMask<1> operator==(VFloat a, VFloat b) { return {a.f == b.f}; }
    friend VMask<1> operator!=(VFloat a, VFloat b) { return {a.f != b.f}; }
    friend VFloat abs(VFloat a) { return std::fabs(a.f); }
    friend VFloat maxAbs(VFloat a, VFloat b) { return max(abs(a), abs(b)); }
    friend VFloat max(VFloat a, VFloat b) { return a.f > b.f ? a.f : b.f; }
    friend VFloat min(VFloat a, VFloat b) { return a.f < b.f ? a.f : b.f; }
    friend VFloat select(VMask<1> m, VFloat a, VFloat b) { return m.b ? a : b; }
    friend float reduceMin(VMask<1> m, VFloat a) { return m.b ? a.f : Infinity; }
    friend float lane(VFloat a, int) { return a.f; }
    friend VFloat withLane(VFloat, int, float x) { return x; }
};

template <> struct VUint<1> {
    uint32_t i;
    VUint() = default;
    VUint(uint32_t x) : i(x) {}
    static VUint loadu(const uint32_t *p) { return *p; }
    static VUint loadBytes(const uint8_t *p) { return *p; }
    void storeu(uint32_t *p) const { *p = i; }
    friend VUint operator^(VUint a, VUint b) { return a.i ^ b.i; }
    friend uint32_t lane(VUint a, int) { return a.i; }
};

inline VFloat<1> lookup8(const float *table, VUint<1> idx) { return table[idx.i]; }
inline VUint<1> lookup8(const uint32_t *table, VUint<1> idx) { return table[idx.i]; }
inline unsigned bitsAt(uint32_t word, VUint<1> idx) { return (word >> idx.i) & 1u; }
inline VFloat<1> lookup16(const float *table, VUint<1> idx) { return table[idx.i]; }
inline VUint<1> lookup16(const uint32_t *table, VUint<1> idx) { return table[idx.i]; }

inline VFloat<1> permute(VFloat<1> a, VUint<1>) { return a; }
inline VUint<1> permute(VUint<1> a, VUint<1>) { return a; }
inline int compressStore(VMask<1> m, VFloat<1> a, float *dst) { *dst = a.f; return m.b ? 1 : 0; }
inline int compressStore(VMask<1> m, VUint<1> a, uint32_t *dst) { *dst = a.i; return m.b ? 1 : 0; }
inline int compressStoreBits(unsigned m, VFloat<1> a, float *dst) { *dst = a.f; return int(m & 1u); }
inline int compressStoreBits(unsigned m, VUint<1> a, uint32_t *dst) { *dst = a.i; return int(m & 1u); }

// ---------------------------------------------------------------------------------------------
// Eight lanes: __m256. Masks live in k registers with AVX-512VL, else in vector registers.

#if NORI_LANES_AVX2
#if NORI_LANES_AVX512
template <> struct VMask<8> {
    __mmask8 k;
    static VMask firstN(uint32_t n) { return {__mmask8(n >= 8 ? 0xFFu : (1u << n) - 1)}; }
    friend VMask operator&(VMask x, VMask y) { return {_kand_mask8(x.k, y.k)}; }
    friend VMask operator|(VMask x, VMask y) { return {_kor_mask8(x.k, y.k)}; }
    friend VMask operator~(VMask x) { return {_knot_mask8(x.k)}; }
    friend bool any(VMask x) { return x.k != 0; }
    friend unsigned bits(VMask x) { return x.k; }
};
#define NORI_CMP8(a, b, p) VMask<8>{_mm256_cmp_ps_mask(a, b, p)}
#else
template <> struct VMask<8> {
    __m256 k;  ///< all ones in the set lanes
    static VMask firstN(uint32_t n) {
        // (No clamp to 8: a signed compare holds for any n below 2^31, more than any list has.)
        __m256i below = _mm256_cmpgt_epi32(_mm256_set1_epi32(int(n)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        return {_mm256_castsi256_ps(below)};
    }
    friend VMask operator&(VMask x, VMask y) { return {_mm256_and_ps(x.k, y.k)}; }
    friend VMask operator|(VMask x, VMask y) { return {_mm256_or_ps(x.k, y.k)}; }
    friend VMask operator~(VMask x) { return {_mm256_xor_ps(x.k, _mm256_castsi256_ps(_mm256_set1_epi32(-1)))}; }
    friend bool any(VMask x) { return !_mm256_testz_ps(x.k, x.k); }
    friend unsigned bits(VMask x) { return unsigned(_mm256_movemask_ps(x.k)); }
};
#define NORI_CMP8(a, b, p) VMask<8>{_mm256_cmp_ps(a, b, p)}
#endif

template <> struct VFloat<8> {
    __m256 v;
    VFloat() = default;
    VFloat(__m256 x) : v(x) {}
    VFloat(float x) : v(_mm256_set1_ps(x)) {}
    static VFloat loadu(const float *p) { return _mm256_loadu_ps(p); }
    static VFloat load(const float *p, VMask<8> m) {
#if NORI_LANES_AVX512
        return _mm256_maskz_loadu_ps(m.k, p);
#else
        return _mm256_maskload_ps(p, _mm256_castps_si256(m.k));
#endif
    }
    void storeu(float *p) const { _mm256_storeu_ps(p, v); }
    friend VFloat operator+(VFloat a, VFloat b) { return _mm256_add_ps(a.v, b.v); }
    friend VFloat operator-(VFloat a, VFloat b) { return _mm256_sub_ps(a.v, b.v); }
    friend VFloat operator*(VFloat a, VFloat b) { return _mm256_mul_ps(a.v, b.v); }
    friend VFloat operator/(VFloat a, VFloat b) { return _mm256_div_ps(a.v, b.v); }
    friend VMask<8> operator<(VFloat a, VFloat b) { return NORI_CMP8(a.v, b.v, _CMP_LT_OQ); }
    friend VMask<8> operator<=(VFloat a, VFloat b) { return NORI_CMP8(a.v, b.v, _CMP_LE_OQ); }
    friend VMask<8> operator>(VFloat a, VFloat b) { return NORI_CMP8(a.v, b.v, _CMP_GT_OQ); }
    friend VMask<8> operator>=(VFloat a, VFloat b) { return NORI_CMP8(a.v, b.v, _CMP_GE_OQ); }
    friend VMask<8> operator==(VFloat a, VFloat b) { return NORI_CMP8(a.v, b.v, _CMP_EQ_OQ); }
    friend VMask<8> operator!=(VFloat a, VFloat b) { return NORI_CMP8(a.v, b.v, _CMP_NEQ_UQ); }
    friend VFloat abs(VFloat a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v); }
    friend VFloat maxAbs(VFloat a, VFloat b) { return max(abs(a), abs(b)); }
    friend VFloat max(VFloat a, VFloat b) { return _mm256_max_ps(a.v, b.v); }
    friend VFloat min(VFloat a, VFloat b) { return _mm256_min_ps(a.v, b.v); }
    friend VFloat select(VMask<8> m, VFloat a, VFloat b) {
#if NORI_LANES_AVX512
        return _mm256_mask_blend_ps(m.k, b.v, a.v);
#else
        return _mm256_blendv_ps(b.v, a.v, m.k);
#endif
    }
    friend float reduceMin(VMask<8> m, VFloat a) {
        __m256 x = select(m, a, VFloat(Infinity)).v;
        __m128 h = _mm_min_ps(_mm256_castps256_ps128(x), _mm256_extractf128_ps(x, 1));
        h = _mm_min_ps(h, _mm_movehl_ps(h, h));
        h = _mm_min_ss(h, _mm_shuffle_ps(h, h, 1));
        return _mm_cvtss_f32(h);
    }
    friend VFloat withLane(VFloat a, int j, float x) {
#if NORI_LANES_AVX512
        return _mm256_mask_broadcastss_ps(a.v, __mmask8(1u << j), _mm_set_ss(x));
#else
        const __m256i at = _mm256_cmpeq_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32(j));
        return _mm256_blendv_ps(a.v, _mm256_set1_ps(x), _mm256_castsi256_ps(at));
#endif
    }
    friend float lane(VFloat a, int j) {
        alignas(32) float x[8];
        _mm256_store_ps(x, a.v);
        return x[j];
    }
};
#undef NORI_CMP8

template <> struct VUint<8> {
    __m256i v;
    VUint() = default;
    VUint(__m256i x) : v(x) {}
    VUint(uint32_t x) : v(_mm256_set1_epi32(int(x))) {}
    static VUint loadu(const uint32_t *p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i *>(p)); }
    static VUint loadBytes(const uint8_t *p) {
        return _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(p)));
    }
    void storeu(uint32_t *p) const { _mm256_storeu_si256(reinterpret_cast<__m256i *>(p), v); }
    friend VUint operator^(VUint a, VUint b) { return _mm256_xor_si256(a.v, b.v); }
    friend uint32_t lane(VUint a, int j) {
        alignas(32) uint32_t x[8];
        _mm256_store_si256(reinterpret_cast<__m256i *>(x), a.v);
        return x[j];
    }
};

inline VFloat<8> permute(VFloat<8> a, VUint<8> idx) { return _mm256_permutevar8x32_ps(a.v, idx.v); }
inline VUint<8> permute(VUint<8> a, VUint<8> idx) { return _mm256_permutevar8x32_epi32(a.v, idx.v); }
// An 8-entry table fits one register: a load and a lane permute instead of a gather.
inline VFloat<8> lookup8(const float *table, VUint<8> idx) { return permute(VFloat<8>::loadu(table), idx); }
inline VUint<8> lookup8(const uint32_t *table, VUint<8> idx) { return permute(VUint<8>::loadu(table), idx); }
// Variable shifts: each lane's bit of the word to the sign bit, gathered as a mask.
inline unsigned bitsAt(uint32_t word, VUint<8> idx) {
    const __m256i bit = _mm256_slli_epi32(_mm256_srlv_epi32(_mm256_set1_epi32(int(word)), idx.v), 31);
    return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(bit)));
}
// A 16-entry table in two registers: both permuted, the upper half's lanes taken where idx >= 8.
inline VFloat<8> lookup16(const float *table, VUint<8> idx) {
    const __m256 upper = _mm256_castsi256_ps(_mm256_slli_epi32(idx.v, 28));  // sign bit = bit 3 of idx
    return _mm256_blendv_ps(permute(VFloat<8>::loadu(table), idx).v, permute(VFloat<8>::loadu(table + 8), idx).v, upper);
}
inline VUint<8> lookup16(const uint32_t *table, VUint<8> idx) {
    const __m256 upper = _mm256_castsi256_ps(_mm256_slli_epi32(idx.v, 28));
    return _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(permute(VUint<8>::loadu(table), idx).v),
                                                _mm256_castsi256_ps(permute(VUint<8>::loadu(table + 8), idx).v), upper));
}

#if NORI_LANES_AVX512
// Register compress plus a full store: compressing straight to memory is slow on some cores.
inline int compressStore(VMask<8> m, VFloat<8> a, float *dst) {
    _mm256_storeu_ps(dst, _mm256_maskz_compress_ps(m.k, a.v));
    return __builtin_popcount(m.k);
}
inline int compressStore(VMask<8> m, VUint<8> a, uint32_t *dst) {
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(dst), _mm256_maskz_compress_epi32(m.k, a.v));
    return __builtin_popcount(m.k);
}
inline int compressStoreBits(unsigned m, VFloat<8> a, float *dst) { return compressStore(VMask<8>{__mmask8(m)}, a, dst); }
inline int compressStoreBits(unsigned m, VUint<8> a, uint32_t *dst) { return compressStore(VMask<8>{__mmask8(m)}, a, dst); }
#else
// AVX2 has no compress instruction: a lane permute whose indices come from a table (byte k of
// entry m = the lane of the k-th set bit of m), branch-free unlike a loop over the set lanes.
struct CompressTable8 {
    uint64_t idx[256];
    constexpr CompressTable8() : idx{} {
        for (unsigned m = 0; m < 256; ++m)
            for (unsigned j = 0, k = 0; j < 8; ++j)
                if (m >> j & 1u) idx[m] |= uint64_t(j) << (8 * k++);
    }
};
inline constexpr CompressTable8 kCompressTable8{};
inline __m256i compressIndex(unsigned m) {
    return _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(kCompressTable8.idx[m & 0xFFu])));
}
inline int compressStoreBits(unsigned m, VFloat<8> a, float *dst) {
    _mm256_storeu_ps(dst, _mm256_permutevar8x32_ps(a.v, compressIndex(m)));
    return __builtin_popcount(m & 0xFFu);
}
inline int compressStoreBits(unsigned m, VUint<8> a, uint32_t *dst) {
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(dst), _mm256_permutevar8x32_epi32(a.v, compressIndex(m)));
    return __builtin_popcount(m & 0xFFu);
}
inline int compressStore(VMask<8> m, VFloat<8> a, float *dst) { return compressStoreBits(bits(m), a, dst); }
inline int compressStore(VMask<8> m, VUint<8> a, uint32_t *dst) { return compressStoreBits(bits(m), a, dst); }
#endif
#endif  // NORI_LANES_AVX2

// ---------------------------------------------------------------------------------------------
// Sixteen lanes: __m512 with __mmask16.

#if NORI_LANES_AVX512
template <> struct VMask<16> {
    __mmask16 k;
    static VMask firstN(uint32_t n) { return {__mmask16(n >= 16 ? 0xFFFFu : (1u << n) - 1)}; }
    // Mask-register instructions, so that masks need not travel through general registers.
    friend VMask operator&(VMask x, VMask y) { return {_kand_mask16(x.k, y.k)}; }
    friend VMask operator|(VMask x, VMask y) { return {_kor_mask16(x.k, y.k)}; }
    friend VMask operator~(VMask x) { return {_knot_mask16(x.k)}; }
    friend bool any(VMask x) { return x.k != 0; }
    friend unsigned bits(VMask x) { return x.k; }
};

template <> struct VFloat<16> {
    __m512 v;
    VFloat() = default;
    VFloat(__m512 x) : v(x) {}
    VFloat(float x) : v(_mm512_set1_ps(x)) {}
    static VFloat loadu(const float *p) { return _mm512_loadu_ps(p); }
    static VFloat load(const float *p, VMask<16> m) { return _mm512_maskz_loadu_ps(m.k, p); }
    void storeu(float *p) const { _mm512_storeu_ps(p, v); }
    friend VFloat operator+(VFloat a, VFloat b) { return _mm512_add_ps(a.v, b.v); }
    friend VFloat operator-(VFloat a, VFloat b) { return _mm512_sub_ps(a.v, b.v); }
    friend VFloat operator*(VFloat a, VFloat b) { return _mm512_mul_ps(a.v, b.v); }
    friend VFloat operator/(VFloat a, VFloat b) { return _mm512_div_ps(a.v, b.v); }
    friend VMask<16> operator<(VFloat a, VFloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)}; }
    friend VMask<16> operator<=(VFloat a, VFloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)}; }
    friend VMask<16> operator>(VFloat a, VFloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GT_OQ)}; }
    friend VMask<16> operator>=(VFloat a, VFloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GE_OQ)}; }
    friend VMask<16> operator==(VFloat a, VFloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_EQ_OQ)}; }
    friend VMask<16> operator!=(VFloat a, VFloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_NEQ_UQ)}; }
    friend VFloat abs(VFloat a) { return _mm512_abs_ps(a.v); }
    // vrangeps, imm 0b1011: the operand of larger magnitude, sign cleared.
    friend VFloat maxAbs(VFloat a, VFloat b) { return _mm512_range_ps(a.v, b.v, 0x0B); }
    friend VFloat max(VFloat a, VFloat b) { return _mm512_max_ps(a.v, b.v); }
    friend VFloat min(VFloat a, VFloat b) { return _mm512_min_ps(a.v, b.v); }
    friend VFloat select(VMask<16> m, VFloat a, VFloat b) { return _mm512_mask_blend_ps(m.k, b.v, a.v); }
    // A blend, not the masked reduction: GCC 12's masked form trips -Wuninitialized.
    friend float reduceMin(VMask<16> m, VFloat a) { return _mm512_reduce_min_ps(select(m, a, VFloat(Infinity)).v); }
    friend VFloat withLane(VFloat a, int j, float x) {
        return _mm512_mask_broadcastss_ps(a.v, __mmask16(1u << j), _mm_set_ss(x));
    }
    friend float lane(VFloat a, int j) {
        alignas(64) float x[16];
        _mm512_store_ps(x, a.v);
        return x[j];
    }
};

template <> struct VUint<16> {
    __m512i v;
    VUint() = default;
    VUint(__m512i x) : v(x) {}
    VUint(uint32_t x) : v(_mm512_set1_epi32(int(x))) {}
    static VUint loadu(const uint32_t *p) { return _mm512_loadu_si512(p); }
    static VUint loadBytes(const uint8_t *p) { return _mm512_cvtepu8_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i *>(p))); }
    void storeu(uint32_t *p) const { _mm512_storeu_si512(p, v); }
    friend VUint operator^(VUint a, VUint b) { return _mm512_xor_si512(a.v, b.v); }
    friend uint32_t lane(VUint a, int j) {
        alignas(64) uint32_t x[16];
        _mm512_store_si512(x, a.v);
        return x[j];
    }
};

inline VFloat<16> permute(VFloat<16> a, VUint<16> idx) { return _mm512_permutexvar_ps(idx.v, a.v); }
inline VUint<16> permute(VUint<16> a, VUint<16> idx) { return _mm512_permutexvar_epi32(idx.v, a.v); }
inline unsigned bitsAt(uint32_t word, VUint<16> idx) {
    return _mm512_test_epi32_mask(_mm512_srlv_epi32(_mm512_set1_epi32(int(word)), idx.v), _mm512_set1_epi32(1));
}
inline VFloat<16> lookup16(const float *table, VUint<16> idx) { return permute(VFloat<16>::loadu(table), idx); }
inline VUint<16> lookup16(const uint32_t *table, VUint<16> idx) { return permute(VUint<16>::loadu(table), idx); }
inline int compressStore(VMask<16> m, VFloat<16> a, float *dst) {
    _mm512_storeu_ps(dst, _mm512_maskz_compress_ps(m.k, a.v));
    return __builtin_popcount(m.k);
}
inline int compressStore(VMask<16> m, VUint<16> a, uint32_t *dst) {
    _mm512_storeu_si512(dst, _mm512_maskz_compress_epi32(m.k, a.v));
    return __builtin_popcount(m.k);
}
inline int compressStoreBits(unsigned m, VFloat<16> a, float *dst) { return compressStore(VMask<16>{__mmask16(m)}, a, dst); }
inline int compressStoreBits(unsigned m, VUint<16> a, uint32_t *dst) { return compressStore(VMask<16>{__mmask16(m)}, a, dst); }
#endif  // NORI_LANES_AVX512

/// Is the lane count \p L compiled into this build?
constexpr bool available(int L) { return L == 1 || (L == 8 && kMaxLanes >= 8) || (L == 16 && kMaxLanes >= 16); }

} // namespace nori::lanes
