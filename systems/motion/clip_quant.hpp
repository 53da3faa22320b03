// Key quantisation of AnimationClip (ClipEncoding::Quantized16) and the decode kernels that
// sample_blocks runs on two key blocks: SSE2 lanes, AVX2 lanes where the CPU has them (chosen at run
// time, clip_decode_avx2.cpp), and a scalar tail, all giving the same bits.
//
// Format: every stored channel c (one component of one joint's translation, rotation or scale) has a
// range [lo, hi] over the clip's keys; a key value v is stored as the 16-bit code
//     q = round((v - lo) / step),   step = (hi - lo) / 65535 (rounded to float),   base = lo,
// and sampled between keys a and b at fraction alpha (wa = 1 - alpha, wb = alpha) as
//     value = base + step * (wa * q_a + wb * q_b).
// Rotations are quantised per component like the rest (the stored chord values keep lerp + normalise
// equal to the source nlerp); constant channels get step 0 and decode exactly. Four range-quantised
// components rather than smallest-three: decoding stays one multiply-add per value, linear in the
// codes (no square root to rebuild a component, no largest-component switch), and the benchmark
// clip still takes 83,444 bytes against ozz-animation's 105,956.
//
// Error bound (channel_error_bound, rotation_error_bound; AnimationClip::error_bound() holds the
// clip's largest): sampling at segment k, fraction alpha against the source evaluated exactly at the
// same point of the clip's timeline (the union of the tracks' key times, times within 1e-6 s merged).
// With ext = hi - lo, M = max(|lo|, |hi|) and u = 2^-24 (float rounding, first order):
//  * quantisation: a key decodes within step/2 of its stored value (nearest code; (hi - lo) / step
//    <= 65535 (1 + u) < 65535.5, so the clamp to [0, 65535] never bites), and so does a lerp of two
//    keys (the weights sum to 1);
//  * float arithmetic: decoding adds <= 3.5 u ext + u M (wa = 1 - alpha rounds by u/2 of a code
//    term <= ext; the two products, their sum and the scaling by step by u ext each; adding base by
//    u M); Float32 decoding adds <= 2.5 u M; the float chord values build_clip stores at other
//    tracks' key times add <= 3 u ext + 2.5 u M (the fraction rounds three times, by 3 u of the
//    key difference <= ext, and the lerp by 2.5 u M). All of it is under 8 u (ext + M), so a
//    channel is within  b = step/2 + 2^-21 (ext + M)  (Float32: step 0);
//  * rotations: the four components are off by a vector e with |e| <= E = sqrt(sum of the four b^2),
//    and the exact un-normalised chord c has |c| >= 1/sqrt(2) (two unit keys with a non-negative dot
//    product), so normalising turns e into at most asin(sqrt(2) E) of 4D angle, twice that of
//    rotation angle; float normalisation (each component rounded by u) adds < 2^-20 rad.
// Worst cases: a rotation whose every component spans [-1, 1] (step 2/65535, E = 3.3e-5) is within
// 9.5e-5 rad (0.0054 degrees; 0.1 mm at 1 m); no quantised clip's rotation bound is larger. A
// translation channel spanning R metres within R / 131070 + 2^-21 (R + M) (7.6 um + 1 um for a
// 1 m range within 1 m of 0). tests/systems/motion/clip_quant_test.cpp checks every key and random times
// of three clips against the bound, and recomputes it from the source keys.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstddef>
#include <cstdint>
#include <span>

namespace aloha {

/// Largest 16-bit code.
inline constexpr uint32_t kQuantMaxCode = 65535u;

/// The dequantisation of one channel: value = base + step * code.
struct QuantChannel {
    float base = 0.0f;  ///< value of code 0 (the channel minimum)
    float step = 0.0f;  ///< value of one code step ((max - min) / 65535; 0 for a constant channel)
};

/// Range of the channel whose key values lie in [lo, hi] (requires finite lo <= hi).
[[nodiscard]] QuantChannel fit_channel(float lo, float hi);
/// Nearest code of `v` (requires v inside the range `c` was fitted to).
[[nodiscard]] uint16_t quantize(float v, const QuantChannel& c);
/// Worst-case |sampled - source lerp| of a channel with key values in [lo, hi] stored with `step`
/// (0 for floats): step/2 + 2^-21 * ((hi - lo) + max(|lo|, |hi|)). (A quantised channel whose step
/// underflowed to 0, a range under ~1e-40, adds hi - lo: the encoder does that.)
[[nodiscard]] float channel_error_bound(float lo, float hi, float step);
/// Worst-case rotation angle (radians) of a joint whose four components are within `component`
/// bounds: 2 asin(min(1, sqrt(2) * |component|)) + 2^-20.
[[nodiscard]] float rotation_error_bound(const float component[4]);

/// Translations / scales: out[i] = base[i] + step[i] * (wa * a[i] + wb * b[i]) for i < count.
/// The decode kernels use AVX2 when the CPU has it and `allow_avx2` (same bits either way).
void decode_lerp(const uint16_t* a, const uint16_t* b, const float* base, const float* step, float wa, float wb,
                 float* out, size_t count, bool allow_avx2 = true);
/// Float keys: out[i] = a[i] * wa + b[i] * wb for i < count.
void decode_lerp(const float* a, const float* b, float wa, float wb, float* out, size_t count, bool allow_avx2 = true);
/// Rotations of `count` joints from four planes (x at a[0..count), y at a[stride..], z, w), dequantised
/// as decode_lerp does, then normalised into `out`.
void decode_nlerp(const uint16_t* a, const uint16_t* b, size_t stride, const float* base, const float* step, float wa,
                  float wb, glm::quat* out, size_t count, bool allow_avx2 = true);
/// Float rotation planes: lerp then normalise into `out`.
void decode_nlerp(const float* a, const float* b, size_t stride, float wa, float wb, glm::quat* out, size_t count,
                  bool allow_avx2 = true);
/// The rotation sampling returns for the un-normalised key value `q` (same normalisation bits).
[[nodiscard]] glm::quat normalize_like_sampling(const glm::quat& q);

/// The AVX2 kernels (clip_decode_avx2.cpp): each handles the leading multiple of 8 and returns it.
namespace clip_simd {
/// True when the CPU (and OS) run AVX2.
[[nodiscard]] bool avx2_available();
size_t decode_lerp_avx2(const uint16_t* a, const uint16_t* b, const float* base, const float* step, float wa, float wb,
                        float* out, size_t count);
size_t decode_lerp_avx2(const float* a, const float* b, float wa, float wb, float* out, size_t count);
size_t decode_nlerp_avx2(const uint16_t* a, const uint16_t* b, size_t stride, const float* base, const float* step,
                         float wa, float wb, glm::quat* out, size_t count);
size_t decode_nlerp_avx2(const float* a, const float* b, size_t stride, float wa, float wb, glm::quat* out,
                         size_t count);
}  // namespace clip_simd

}  // namespace aloha
