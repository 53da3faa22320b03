// AVX2 forms of the clip decode kernels (clip_quant.hpp), compiled for AVX2 with a target attribute
// and chosen at run time when the CPU has it. Eight lanes of exactly the scalar operations, in the
// same order, with no FMA: the bits equal the SSE2 and scalar paths' (tests compare them).
#include "systems/motion/clip_quant.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

#define ALOHA_AVX2 __attribute__((target("avx2")))

namespace aloha::clip_simd {

namespace {

// Eight uint16 codes at p as floats.
ALOHA_AVX2 inline __m256 load8_codes(const uint16_t* p) {
    return _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))));
}

// Normalises eight quaternions given as x, y, z, w lanes and stores them as eight glm::quat.
ALOHA_AVX2 inline void store8_normalized(__m256 x, __m256 y, __m256 z, __m256 w, glm::quat* out) {
    const __m256 d = _mm256_add_ps(
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(x, x), _mm256_mul_ps(y, y)), _mm256_mul_ps(z, z)), _mm256_mul_ps(w, w));
    const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(d));
    x = _mm256_mul_ps(x, inv);
    y = _mm256_mul_ps(y, inv);
    z = _mm256_mul_ps(z, inv);
    w = _mm256_mul_ps(w, inv);
    // 4x4 transposes inside each 128-bit half: q[i] = quaternion i of the half.
    const __m256 t0 = _mm256_unpacklo_ps(x, y), t1 = _mm256_unpackhi_ps(x, y);
    const __m256 t2 = _mm256_unpacklo_ps(z, w), t3 = _mm256_unpackhi_ps(z, w);
    const __m256 q0 = _mm256_shuffle_ps(t0, t2, 0x44), q1 = _mm256_shuffle_ps(t0, t2, 0xEE);  // joints 0|4, 1|5
    const __m256 q2 = _mm256_shuffle_ps(t1, t3, 0x44), q3 = _mm256_shuffle_ps(t1, t3, 0xEE);  // joints 2|6, 3|7
    float* o = &out->x;
    _mm256_storeu_ps(o, _mm256_permute2f128_ps(q0, q1, 0x20));
    _mm256_storeu_ps(o + 8, _mm256_permute2f128_ps(q2, q3, 0x20));
    _mm256_storeu_ps(o + 16, _mm256_permute2f128_ps(q0, q1, 0x31));
    _mm256_storeu_ps(o + 24, _mm256_permute2f128_ps(q2, q3, 0x31));
}

// Lanes o..o+7 of the lerp of two quantised key blocks: base + step * (wa * a + wb * b).
struct QuantLerp8 {
    const uint16_t* a;
    const uint16_t* b;
    const float* base;
    const float* step;
    float wa, wb;
    [[nodiscard]] ALOHA_AVX2 __m256 eight(size_t o) const {
        const __m256 mix = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(wa), load8_codes(a + o)),
                                         _mm256_mul_ps(_mm256_set1_ps(wb), load8_codes(b + o)));
        return _mm256_add_ps(_mm256_loadu_ps(base + o), _mm256_mul_ps(_mm256_loadu_ps(step + o), mix));
    }
};

// Lanes o..o+7 of the lerp of two float key blocks: a * wa + b * wb.
struct FloatLerp8 {
    const float* a;
    const float* b;
    float wa, wb;
    [[nodiscard]] ALOHA_AVX2 __m256 eight(size_t o) const {
        return _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(a + o), _mm256_set1_ps(wa)),
                             _mm256_mul_ps(_mm256_loadu_ps(b + o), _mm256_set1_ps(wb)));
    }
};

// out[i] = l(i) for the leading multiple of 8 of count; returns it.
template <class Lerp>
ALOHA_AVX2 size_t lerp8(const Lerp& l, float* out, size_t count) {
    size_t i = 0;
    for (; i + 8 <= count; i += 8) _mm256_storeu_ps(out + i, l.eight(i));
    return i;
}

// Rotations of the leading multiple of 8 of count joints: component p of joint j is l(p * stride + j),
// normalised into out[j]; returns how many.
template <class Lerp>
ALOHA_AVX2 size_t nlerp8(const Lerp& l, size_t stride, glm::quat* out, size_t count) {
    size_t j = 0;
    for (; j + 8 <= count; j += 8)
        store8_normalized(l.eight(j), l.eight(stride + j), l.eight(2 * stride + j), l.eight(3 * stride + j), out + j);
    return j;
}

}  // namespace

bool avx2_available() {
    static const bool available = [] {
        __builtin_cpu_init();  // in case this first runs from a static constructor
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return available;
}

ALOHA_AVX2 size_t decode_lerp_avx2(const uint16_t* a, const uint16_t* b, const float* base, const float* step,
                                   float wa, float wb, float* out, size_t count) {
    return lerp8(QuantLerp8{a, b, base, step, wa, wb}, out, count);
}

ALOHA_AVX2 size_t decode_lerp_avx2(const float* a, const float* b, float wa, float wb, float* out, size_t count) {
    return lerp8(FloatLerp8{a, b, wa, wb}, out, count);
}

ALOHA_AVX2 size_t decode_nlerp_avx2(const uint16_t* a, const uint16_t* b, size_t stride, const float* base,
                                    const float* step, float wa, float wb, glm::quat* out, size_t count) {
    return nlerp8(QuantLerp8{a, b, base, step, wa, wb}, stride, out, count);
}

ALOHA_AVX2 size_t decode_nlerp_avx2(const float* a, const float* b, size_t stride, float wa, float wb, glm::quat* out,
                                    size_t count) {
    return nlerp8(FloatLerp8{a, b, wa, wb}, stride, out, count);
}

}  // namespace aloha::clip_simd

#else  // no AVX2 forms: the SSE2 / scalar paths do everything

namespace aloha::clip_simd {

bool avx2_available() { return false; }
size_t decode_lerp_avx2(const uint16_t*, const uint16_t*, const float*, const float*, float, float, float*, size_t) {
    return 0;
}
size_t decode_lerp_avx2(const float*, const float*, float, float, float*, size_t) { return 0; }
size_t decode_nlerp_avx2(const uint16_t*, const uint16_t*, size_t, const float*, const float*, float, float, glm::quat*,
                         size_t) {
    return 0;
}
size_t decode_nlerp_avx2(const float*, const float*, size_t, float, float, glm::quat*, size_t) { return 0; }

}  // namespace aloha::clip_simd

#endif
