// AVX2 form of local_to_model (local_to_model.hpp), compiled for AVX2 with a target attribute and chosen
// at run time when the CPU has it. The local matrices of 8 joints at a time are built with one joint per
// lane (structure of arrays, like ozz-animation's SoaTransform), then the parent products run joint by
// joint with two model columns per 256-bit operation, the parent's columns kept in registers when it is
// the previous joint. Every value is the portable loop's expression evaluated in the same order with
// the same roundings (no FMA; a - b as a + (-b), 2x as x + x, adding -0 as the identity): same bits,
// which tests/systems/motion/pose_test.cpp checks.
#include "systems/motion/local_to_model.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

#include <algorithm>

#define ALOHA_AVX2 __attribute__((target("avx2")))

namespace aloha::l2m_simd {

namespace {

static_assert(sizeof(glm::mat4) == 16 * sizeof(float) && sizeof(glm::quat) == 4 * sizeof(float) &&
                  sizeof(glm::vec3) == 3 * sizeof(float),
              "local_to_model_avx2 reads GLM types as packed floats");

constexpr size_t kChunk = 8;  // joints per local-matrix batch (one per AVX2 lane)
constexpr size_t kGroup = 2;  // poses run together by local_to_model_many

// Per-joint operands of the model product: a = [column 0 | column 1] and b = [column 2 | translation] of
// the local matrix (lane 3 of each half unused).
struct LocalColumns {
    __m256 a, b;
};

// 4x4 transpose inside each 128-bit half: rows r0..r3 in, columns out (in place).
ALOHA_AVX2 inline void transpose4(__m256& r0, __m256& r1, __m256& r2, __m256& r3) {
    const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
    const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
    r0 = _mm256_shuffle_ps(t0, t2, 0x44);
    r1 = _mm256_shuffle_ps(t0, t2, 0xEE);
    r2 = _mm256_shuffle_ps(t1, t3, 0x44);
    r3 = _mm256_shuffle_ps(t1, t3, 0xEE);
}

// How a chunk of 8 joints may be read: kInner chunks are followed by more joints, so every element
// (a vec3 too) is read with 16 bytes; the last chunk reads its last vec3 exactly (kLastFull: all 8
// joints present; kPartial: only the first n, the rest read as zero).
enum class Reads { kInner, kLastFull, kPartial };

// Element i (`kStride` floats at p) as four floats (lane 3 of a vec3 unused), read as `kReads` allows.
template <Reads kReads, size_t kStride>
ALOHA_AVX2 inline __m128 load_element(const float* p, size_t i, size_t n) {
    if constexpr (kReads == Reads::kPartial)
        if (i >= n) return _mm_setzero_ps();
    if constexpr (kReads != Reads::kInner && kStride == 3)
        if (i + 1 == n) return _mm_setr_ps(p[3 * i], p[3 * i + 1], p[3 * i + 2], 0.0f);
    return _mm_loadu_ps(p + kStride * i);
}

// Elements 0..7 of `kStride` floats at p, transposed: lane i of out[c] is component c of element i.
template <Reads kReads, size_t kStride>
ALOHA_AVX2 inline void load_soa(const float* p, size_t n, __m256 out[4]) {
    for (size_t i = 0; i < 4; ++i)
        out[i] = _mm256_insertf128_ps(_mm256_castps128_ps256(load_element<kReads, kStride>(p, i, n)),
                                      load_element<kReads, kStride>(p, i + 4, n), 1);
    transpose4(out[0], out[1], out[2], out[3]);
}

// 1 - 2 (a + b), with 2 e as e + e (exact, as the portable loop's 2.0f * e).
ALOHA_AVX2 inline __m256 diag(__m256 a, __m256 b) {
    const __m256 e = _mm256_add_ps(a, b);
    return _mm256_sub_ps(_mm256_set1_ps(1.0f), _mm256_add_ps(e, e));
}

// 2 e as e + e.
ALOHA_AVX2 inline __m256 twice(__m256 e) { return _mm256_add_ps(e, e); }

// The local matrices of 8 joints (rotation columns scaled per axis, then the translation), as the
// portable loop writes them, with one lane per joint: products xx.. wz, then
//   column 0 = [1 - 2 (yy + zz), 2 (xy + wz), 2 (xz - wy)] sx,
//   column 1 = [2 (xy - wz), 1 - 2 (xx + zz), 2 (yz + wx)] sy,
//   column 2 = [2 (xz + wy), 2 (yz - wx), 1 - 2 (xx + yy)] sz.
// t, q, s point at joint 0 of the 8, read as `kReads` allows (load_element).
template <Reads kReads>
ALOHA_AVX2 inline void local_columns8(const float* t, const float* q, const float* s, size_t n,
                                      LocalColumns out[kChunk]) {
    __m256 qv[4], sv[4];
    load_soa<kReads, 4>(q, n, qv);
    load_soa<kReads, 3>(s, n, sv);
    const __m256 x = qv[0], y = qv[1], z = qv[2], w = qv[3];
    const __m256 xx = _mm256_mul_ps(x, x), yy = _mm256_mul_ps(y, y), zz = _mm256_mul_ps(z, z);
    const __m256 xy = _mm256_mul_ps(x, y), xz = _mm256_mul_ps(x, z), yz = _mm256_mul_ps(y, z);
    const __m256 wx = _mm256_mul_ps(w, x), wy = _mm256_mul_ps(w, y), wz = _mm256_mul_ps(w, z);
    __m256 c0[4] = {_mm256_mul_ps(diag(yy, zz), sv[0]), _mm256_mul_ps(twice(_mm256_add_ps(xy, wz)), sv[0]),
                    _mm256_mul_ps(twice(_mm256_sub_ps(xz, wy)), sv[0]), _mm256_setzero_ps()};
    __m256 c1[4] = {_mm256_mul_ps(twice(_mm256_sub_ps(xy, wz)), sv[1]), _mm256_mul_ps(diag(xx, zz), sv[1]),
                    _mm256_mul_ps(twice(_mm256_add_ps(yz, wx)), sv[1]), _mm256_setzero_ps()};
    __m256 c2[4] = {_mm256_mul_ps(twice(_mm256_add_ps(xz, wy)), sv[2]),
                    _mm256_mul_ps(twice(_mm256_sub_ps(yz, wx)), sv[2]), _mm256_mul_ps(diag(xx, yy), sv[2]),
                    _mm256_setzero_ps()};
    // Back to one joint per row: c?[i] = [joint i | joint i + 4].
    transpose4(c0[0], c0[1], c0[2], c0[3]);
    transpose4(c1[0], c1[1], c1[2], c1[3]);
    transpose4(c2[0], c2[1], c2[2], c2[3]);
    for (size_t i = 0; i < 4; ++i) {
        out[i].a = _mm256_permute2f128_ps(c0[i], c1[i], 0x20);
        out[i + 4].a = _mm256_permute2f128_ps(c0[i], c1[i], 0x31);
        out[i].b = _mm256_insertf128_ps(c2[i], load_element<kReads, 3>(t, i, n), 1);
        out[i + 4].b =
            _mm256_permute2f128_ps(c2[i], _mm256_castps128_ps256(load_element<kReads, 3>(t, i + 4, n)), 0x21);
    }
}

// Model columns 0 | 1 and 2 | 3 of one joint from its local columns and its parent's columns
// p0 = [c0 | c0], p1 = [c1 | c1], p2 = [c2 | c2], p3 = [-0 | c3]: ((p0 l_k0 + p1 l_k1) + p2 l_k2)
// (+ p3 for the translation), the portable order.
ALOHA_AVX2 inline void model_columns(const LocalColumns& l, __m256 p0, __m256 p1, __m256 p2, __m256 p3, __m256* m01,
                                     __m256* m23) {
    *m01 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(p0, _mm256_permute_ps(l.a, 0x00)),
                                       _mm256_mul_ps(p1, _mm256_permute_ps(l.a, 0x55))),
                         _mm256_mul_ps(p2, _mm256_permute_ps(l.a, 0xAA)));
    *m23 = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(p0, _mm256_permute_ps(l.b, 0x00)),
                                                     _mm256_mul_ps(p1, _mm256_permute_ps(l.b, 0x55))),
                                       _mm256_mul_ps(p2, _mm256_permute_ps(l.b, 0xAA))),
                         p3);
}

// Local columns of joints [first, first + 8) of one pose into `out` (n of them present).
ALOHA_AVX2 inline void local_chunk(const PosePointers& pose, size_t first, size_t n, size_t count,
                                   LocalColumns out[kChunk]) {
    const float* t = &pose.translations[first].x;
    const float* q = &pose.rotations[first].x;
    const float* s = &pose.scales[first].x;
    if (first + kChunk < count) local_columns8<Reads::kInner>(t, q, s, n, out);
    else if (n == kChunk) local_columns8<Reads::kLastFull>(t, q, s, n, out);
    else local_columns8<Reads::kPartial>(t, q, s, n, out);
}

// local_to_model for K poses of one skeleton, joint by joint together: their parent chains are
// independent, so the K products of a joint overlap instead of waiting on one chain's latency.
template <size_t K>
ALOHA_AVX2 void run_group(const int16_t* parents, const PosePointers* poses, const float* top, size_t count) {
    const __m256 negzero = _mm256_set1_ps(-0.0f);
    float* out[K];
    __m256 m01[K], m23[K];
    for (size_t c = 0; c < K; ++c) {
        out[c] = &poses[c].model[0][0].x;
        m01[c] = _mm256_setzero_ps();
        m23[c] = _mm256_setzero_ps();
    }
    LocalColumns local[K][kChunk];
    for (size_t first = 0; first < count; first += kChunk) {
        const size_t n = std::min(kChunk, count - first);
        for (size_t c = 0; c < K; ++c) local_chunk(poses[c], first, n, count, local[c]);
        for (size_t i = 0; i < n; ++i) {
            const size_t j = first + i;
            const int p = parents[j];
            if (p >= 0 && static_cast<size_t>(p) + 1 == j) {
                // Parent is the previous joint: its columns are still in registers (no store-to-load trip).
                for (size_t c = 0; c < K; ++c) {
                    const __m256 p0 = _mm256_permute2f128_ps(m01[c], m01[c], 0x00);
                    const __m256 p1 = _mm256_permute2f128_ps(m01[c], m01[c], 0x11);
                    const __m256 p2 = _mm256_permute2f128_ps(m23[c], m23[c], 0x00);
                    const __m256 p3 = _mm256_blend_ps(negzero, m23[c], 0xF0);
                    model_columns(local[c][i], p0, p1, p2, p3, &m01[c], &m23[c]);
                }
            } else {
                for (size_t c = 0; c < K; ++c) {
                    const float* pm = p < 0 ? top : out[c] + 16 * static_cast<size_t>(p);
                    const __m256 p0 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(pm));
                    const __m256 p1 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(pm + 4));
                    const __m256 p2 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(pm + 8));
                    const __m256 p3 = _mm256_insertf128_ps(negzero, _mm_loadu_ps(pm + 12), 1);
                    model_columns(local[c][i], p0, p1, p2, p3, &m01[c], &m23[c]);
                }
            }
            for (size_t c = 0; c < K; ++c) {
                _mm256_storeu_ps(out[c] + 16 * j, m01[c]);
                _mm256_storeu_ps(out[c] + 16 * j + 8, m23[c]);
            }
        }
    }
}

}  // namespace

ALOHA_AVX2 void local_to_model_avx2(const int16_t* parents, const PosePointers* poses, size_t pose_count,
                                    const glm::mat4& top, size_t count) {
    if (count == 0) return;
    size_t c = 0;
    for (; c + kGroup <= pose_count; c += kGroup) run_group<kGroup>(parents, poses + c, &top[0].x, count);
    for (; c < pose_count; ++c) run_group<1>(parents, poses + c, &top[0].x, count);
}

}  // namespace aloha::l2m_simd

#else  // no AVX2 form: local_to_model runs its portable loop

#include <cassert>

namespace aloha::l2m_simd {

void local_to_model_avx2(const int16_t*, const PosePointers*, size_t, const glm::mat4&, size_t) {
    assert(false && "local_to_model_avx2 called where clip_simd::avx2_available() is false");
}

}  // namespace aloha::l2m_simd

#endif
