#include "systems/motion/clip_quant.hpp"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define ALOHA_CLIP_SSE2 1
#endif

namespace aloha {

#ifdef GLM_FORCE_QUAT_DATA_WXYZ
#error "decode_nlerp writes quaternions as x, y, z, w"
#endif
static_assert(sizeof(glm::quat) == 4 * sizeof(float), "glm::quat must be four packed floats");

namespace {

// `b` rounded up to a float, so a bound stored as float is never below the real one.
float round_up(double b) {
    float f = static_cast<float>(b);
    if (static_cast<double>(f) < b) f = std::nextafter(f, HUGE_VALF);
    return f;
}

}  // namespace

QuantChannel fit_channel(float lo, float hi) {
    QuantChannel c;
    c.base = lo;
    const double ext = static_cast<double>(hi) - static_cast<double>(lo);
    c.step = ext > 0.0 ? static_cast<float>(ext / static_cast<double>(kQuantMaxCode)) : 0.0f;
    // A range under ~1e-40 whose step underflows to 0 decodes as its minimum (error <= hi - lo).
    return c;
}

uint16_t quantize(float v, const QuantChannel& c) {
    if (!(c.step > 0.0f)) return 0;
    const double u = (static_cast<double>(v) - static_cast<double>(c.base)) / static_cast<double>(c.step);
    return static_cast<uint16_t>(std::clamp(std::nearbyint(u), 0.0, static_cast<double>(kQuantMaxCode)));
}

float channel_error_bound(float lo, float hi, float step) {
    const double ext = static_cast<double>(hi) - static_cast<double>(lo);
    const double m = std::max(std::abs(static_cast<double>(lo)), std::abs(static_cast<double>(hi)));
    return round_up(0.5 * static_cast<double>(step) + std::ldexp(ext + m, -21));
}

float rotation_error_bound(const float component[4]) {
    double e2 = 0.0;
    for (int c = 0; c < 4; ++c) e2 += static_cast<double>(component[c]) * static_cast<double>(component[c]);
    const double s = std::min(1.0, std::sqrt(2.0 * e2));
    return round_up(2.0 * std::asin(s) + std::ldexp(1.0, -20));
}

namespace {

inline bool use_avx2(bool allow) { return allow && clip_simd::avx2_available(); }

// The scalar forms: every vector lane below computes exactly these operations in this order.
inline float lerp_q(uint16_t a, uint16_t b, float base, float step, float wa, float wb) {
    return base + step * (wa * static_cast<float>(a) + wb * static_cast<float>(b));
}

inline float lerp_f(float a, float b, float wa, float wb) { return a * wa + b * wb; }

inline void store_normalized(float x, float y, float z, float w, glm::quat* out) {
    const float inv = 1.0f / std::sqrt(x * x + y * y + z * z + w * w);
    float* o = &out->x;
    o[0] = x * inv;
    o[1] = y * inv;
    o[2] = z * inv;
    o[3] = w * inv;
}

#ifdef ALOHA_CLIP_SSE2
// Four uint16 codes (8 bytes at p) as floats.
inline __m128 load4_codes(const uint16_t* p) {
    const __m128i v = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
    return _mm_cvtepi32_ps(_mm_unpacklo_epi16(v, _mm_setzero_si128()));
}

// Normalises four quaternions given as x, y, z, w lanes and stores them as four glm::quat.
inline void store4_normalized(__m128 x, __m128 y, __m128 z, __m128 w, glm::quat* out) {
    const __m128 d = _mm_add_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z)),
                                _mm_mul_ps(w, w));
    const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(d));
    x = _mm_mul_ps(x, inv);
    y = _mm_mul_ps(y, inv);
    z = _mm_mul_ps(z, inv);
    w = _mm_mul_ps(w, inv);
    _MM_TRANSPOSE4_PS(x, y, z, w);  // lanes -> one quaternion per register
    float* o = &out->x;
    _mm_storeu_ps(o, x);
    _mm_storeu_ps(o + 4, y);
    _mm_storeu_ps(o + 8, z);
    _mm_storeu_ps(o + 12, w);
}
#endif

// Element o of the lerp of two quantised key blocks: one() scalar, four() SSE2 lanes o..o+3.
struct QuantLerp {
    const uint16_t* a;
    const uint16_t* b;
    const float* base;
    const float* step;
    float wa, wb;
    [[nodiscard]] float one(size_t o) const { return lerp_q(a[o], b[o], base[o], step[o], wa, wb); }
#ifdef ALOHA_CLIP_SSE2
    [[nodiscard]] __m128 four(size_t o) const {
        const __m128 mix = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(wa), load4_codes(a + o)),
                                      _mm_mul_ps(_mm_set1_ps(wb), load4_codes(b + o)));
        return _mm_add_ps(_mm_loadu_ps(base + o), _mm_mul_ps(_mm_loadu_ps(step + o), mix));
    }
#endif
};

// Element o of the lerp of two float key blocks, as QuantLerp.
struct FloatLerp {
    const float* a;
    const float* b;
    float wa, wb;
    [[nodiscard]] float one(size_t o) const { return lerp_f(a[o], b[o], wa, wb); }
#ifdef ALOHA_CLIP_SSE2
    [[nodiscard]] __m128 four(size_t o) const {
        return _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(a + o), _mm_set1_ps(wa)), _mm_mul_ps(_mm_loadu_ps(b + o), _mm_set1_ps(wb)));
    }
#endif
};

// out[i] = l(i) for i in [i, count): four lanes at a time, then the scalar tail.
template <class Lerp>
void lerp_from(size_t i, const Lerp& l, float* out, size_t count) {
#ifdef ALOHA_CLIP_SSE2
    for (; i + 4 <= count; i += 4) _mm_storeu_ps(out + i, l.four(i));
#endif
    for (; i < count; ++i) out[i] = l.one(i);
}

// Rotations [j, count): component p of joint j is l(p * stride + j), normalised into out[j].
template <class Lerp>
void nlerp_from(size_t j, const Lerp& l, size_t stride, glm::quat* out, size_t count) {
#ifdef ALOHA_CLIP_SSE2
    for (; j + 4 <= count; j += 4)
        store4_normalized(l.four(j), l.four(stride + j), l.four(2 * stride + j), l.four(3 * stride + j), out + j);
#endif
    for (; j < count; ++j)
        store_normalized(l.one(j), l.one(stride + j), l.one(2 * stride + j), l.one(3 * stride + j), out + j);
}

}  // namespace

void decode_lerp(const uint16_t* a, const uint16_t* b, const float* base, const float* step, float wa, float wb,
                 float* out, size_t count, bool allow_avx2) {
    const size_t i = use_avx2(allow_avx2) ? clip_simd::decode_lerp_avx2(a, b, base, step, wa, wb, out, count) : 0;
    lerp_from(i, QuantLerp{a, b, base, step, wa, wb}, out, count);
}

void decode_lerp(const float* a, const float* b, float wa, float wb, float* out, size_t count, bool allow_avx2) {
    const size_t i = use_avx2(allow_avx2) ? clip_simd::decode_lerp_avx2(a, b, wa, wb, out, count) : 0;
    lerp_from(i, FloatLerp{a, b, wa, wb}, out, count);
}

void decode_nlerp(const uint16_t* a, const uint16_t* b, size_t stride, const float* base, const float* step, float wa,
                  float wb, glm::quat* out, size_t count, bool allow_avx2) {
    const size_t j =
        use_avx2(allow_avx2) ? clip_simd::decode_nlerp_avx2(a, b, stride, base, step, wa, wb, out, count) : 0;
    nlerp_from(j, QuantLerp{a, b, base, step, wa, wb}, stride, out, count);
}

void decode_nlerp(const float* a, const float* b, size_t stride, float wa, float wb, glm::quat* out, size_t count,
                  bool allow_avx2) {
    const size_t j = use_avx2(allow_avx2) ? clip_simd::decode_nlerp_avx2(a, b, stride, wa, wb, out, count) : 0;
    nlerp_from(j, FloatLerp{a, b, wa, wb}, stride, out, count);
}

glm::quat normalize_like_sampling(const glm::quat& q) {
    glm::quat r;
    store_normalized(q.x, q.y, q.z, q.w, &r);
    return r;
}

}  // namespace aloha
