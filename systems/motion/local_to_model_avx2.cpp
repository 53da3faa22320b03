// AVX2 form of local_to_model (local_to_model.hpp), compiled for AVX2 with a target attribute and chosen
// at run time when the CPU has it. One joint at a time, like the portable loop, but the local matrix is
// built with eight-lane shuffles and products instead of scalar ones and two model columns are formed
// per 256-bit operation. Every value is the portable loop's expression evaluated in the same order with
// the same roundings (no FMA; a - b as a + (-b), 2x as x + x, adding -0 as the identity): same bits,
// which tests/systems/motion/pose_test.cpp checks.
#include "systems/motion/local_to_model.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

#define ALOHA_AVX2 __attribute__((target("avx2")))

namespace aloha::l2m_simd {

namespace {

static_assert(sizeof(glm::mat4) == 16 * sizeof(float) && sizeof(glm::quat) == 4 * sizeof(float) &&
                  sizeof(glm::vec3) == 3 * sizeof(float),
              "local_to_model_avx2 reads GLM types as packed floats");

// The local matrix (rotation columns scaled per axis) from the quaternion q = (x, y, z, w), as the
// portable loop writes it: with products xx.. wz,
//   d = 1 - 2 [yy + zz, xx + zz, xx + yy],  P = 2 [xy + wz, yz + wx, zx + wy],  M = 2 [xy - wz, yz - wx, zx - wy],
//   column 0 = [d0 P0 M2] sx,  column 1 = [M0 d1 P1] sy,  column 2 = [P2 M1 d2] sz:
// d and M already sit in their lanes; P rotated by one lane (Pr = [P2 P0 P1]) fills the rest. Every
// operation runs on both 128-bit halves (q in both), so columns 0 | 1 come out of one blend pair.
// Shuffle immediates: lane i of the result takes lane (imm >> 2i) & 3.
constexpr int kYzx = _MM_SHUFFLE(3, 0, 2, 1);  // [y z x .]
constexpr int kZxy = _MM_SHUFFLE(3, 1, 0, 2);  // [z x y .]
constexpr int kW = _MM_SHUFFLE(3, 3, 3, 3);
constexpr int kYxx = _MM_SHUFFLE(3, 0, 0, 1);
constexpr int kZzy = _MM_SHUFFLE(3, 1, 2, 2);

// x, y, z of `v` in lanes 0-2. kLast reads exactly the 12 bytes of v; otherwise 16 (the caller
// guarantees the next element follows; lane 3 of the translation is never used).
template <bool kLast>
ALOHA_AVX2 inline __m128 load3(const float* v) {
    if constexpr (kLast) return _mm_setr_ps(v[0], v[1], v[2], 0.0f);
    else return _mm_loadu_ps(v);
}

// model = parent * TRS(t, q, s) for one joint, model columns 0 | 1 in m01 and 2 | 3 in m23; the
// parent's columns come as p0 = [c0 | c0], p1 = [c1 | c1], p2 = [c2 | c2], p3 = [-0 | c3].
template <bool kLast>
ALOHA_AVX2 inline void joint(const float* t, const float* q, const float* s, __m256 p0, __m256 p1, __m256 p2,
                             __m256 p3, __m256* m01, __m256* m23) {
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256 q8 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(q));
    const __m256 qq = _mm256_mul_ps(q8, q8);
    const __m256 pr = _mm256_mul_ps(q8, _mm256_shuffle_ps(q8, q8, kYzx));                  // xy yz zx
    const __m256 wq = _mm256_mul_ps(_mm256_shuffle_ps(q8, q8, kW), q8);                    // wx wy wz
    const __m256 wz = _mm256_shuffle_ps(wq, wq, kZxy);                                     // wz wx wy
    const __m256 sum = _mm256_add_ps(_mm256_shuffle_ps(qq, qq, kYxx), _mm256_shuffle_ps(qq, qq, kZzy));
    const __m256 d = _mm256_sub_ps(one, _mm256_add_ps(sum, sum));
    const __m256 plus = _mm256_add_ps(pr, wz), minus = _mm256_sub_ps(pr, wz);
    const __m256 p = _mm256_add_ps(plus, plus), m = _mm256_add_ps(minus, minus);
    const __m256 prot = _mm256_shuffle_ps(p, p, kZxy);                                     // P2 P0 P1
    // Lanes: column 0 = [d P M] in the lower half, column 1 = [M d P] in the upper; column 2 = [P M d].
    const __m256 c01 = _mm256_blend_ps(_mm256_blend_ps(d, prot, 0x42), m, 0x14);
    const __m128 c2 = _mm_blend_ps(_mm_blend_ps(_mm256_castps256_ps128(d), _mm256_castps256_ps128(prot), 0x1),
                                   _mm256_castps256_ps128(m), 0x2);
    // Scales: sx on the lower half, sy on the upper, then sz.
    const __m256 s01 = _mm256_blend_ps(_mm256_broadcast_ss(s), _mm256_broadcast_ss(s + 1), 0xF0);
    const __m256 col01 = _mm256_mul_ps(c01, s01);
    const __m128 col2 = _mm_mul_ps(c2, _mm_broadcast_ss(s + 2));
    const __m256 col2t = _mm256_insertf128_ps(_mm256_castps128_ps256(col2), load3<kLast>(t), 1);
    // Model columns: ((p0 l_c0 + p1 l_c1) + p2 l_c2) (+ p3 for the translation), the portable order.
    *m01 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(p0, _mm256_permute_ps(col01, 0x00)),
                                       _mm256_mul_ps(p1, _mm256_permute_ps(col01, 0x55))),
                         _mm256_mul_ps(p2, _mm256_permute_ps(col01, 0xAA)));
    *m23 = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(p0, _mm256_permute_ps(col2t, 0x00)),
                                                     _mm256_mul_ps(p1, _mm256_permute_ps(col2t, 0x55))),
                                       _mm256_mul_ps(p2, _mm256_permute_ps(col2t, 0xAA))),
                         p3);
}

// Runs joints [first, end) (kLast: the one last joint of the array, whose vec3 reads stop at its end).
template <bool kLast>
ALOHA_AVX2 inline void joints(const int16_t* parents, const float* t, const float* q, const float* s,
                              const float* top, float* out, size_t first, size_t end, __m256* m01, __m256* m23) {
    const __m256 negzero = _mm256_set1_ps(-0.0f);
    for (size_t j = first; j < end; ++j) {
        const int p = parents[j];
        __m256 p0, p1, p2, p3;
        if (p >= 0 && static_cast<size_t>(p) + 1 == j) {
            // Parent is the previous joint: its columns are still in registers (no store-to-load trip).
            p0 = _mm256_permute2f128_ps(*m01, *m01, 0x00);
            p1 = _mm256_permute2f128_ps(*m01, *m01, 0x11);
            p2 = _mm256_permute2f128_ps(*m23, *m23, 0x00);
            p3 = _mm256_blend_ps(negzero, *m23, 0xF0);
        } else {
            const float* pm = p < 0 ? top : out + 16 * static_cast<size_t>(p);
            p0 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(pm));
            p1 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(pm + 4));
            p2 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(pm + 8));
            p3 = _mm256_insertf128_ps(negzero, _mm_loadu_ps(pm + 12), 1);
        }
        joint<kLast>(t + 3 * j, q + 4 * j, s + 3 * j, p0, p1, p2, p3, m01, m23);
        _mm256_storeu_ps(out + 16 * j, *m01);
        _mm256_storeu_ps(out + 16 * j + 8, *m23);
    }
}

}  // namespace

ALOHA_AVX2 void local_to_model_avx2(const int16_t* parents, const glm::vec3* translations, const glm::quat* rotations,
                                    const glm::vec3* scales, const glm::mat4& top, glm::mat4* model, size_t count) {
    if (count == 0) return;
    const float* t = &translations[0].x;
    const float* q = &rotations[0].x;
    const float* s = &scales[0].x;
    float* out = &model[0][0].x;
    __m256 m01 = _mm256_setzero_ps(), m23 = _mm256_setzero_ps();
    joints<false>(parents, t, q, s, &top[0].x, out, 0, count - 1, &m01, &m23);
    joints<true>(parents, t, q, s, &top[0].x, out, count - 1, count, &m01, &m23);
}

}  // namespace aloha::l2m_simd

#else  // no AVX2 form: local_to_model runs its portable loop

namespace aloha::l2m_simd {

void local_to_model_avx2(const int16_t*, const glm::vec3*, const glm::quat*, const glm::vec3*, const glm::mat4&,
                         glm::mat4*, size_t) {}

}  // namespace aloha::l2m_simd

#endif
