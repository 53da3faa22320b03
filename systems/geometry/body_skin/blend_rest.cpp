// Scalar and SSE2 forms of the blended skin's spring roots and rest ends (see blend_rest.hpp).
#include "systems/geometry/body_skin/blend_rest.hpp"

#include "systems/geometry/spring_skin/grid_sample.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define ALOHA_BLEND_SSE2 1
#endif

// Where the build's baseline lacks AVX (GCC/Clang on x86-64), the four-lane kernels are compiled a second time with
// AVX's three-operand (VEX) encoding of the same 128-bit operations, chosen at run time when the CPU has AVX: fewer
// register copies, and the same results (AVX brings no FMA).
#if defined(ALOHA_BLEND_SSE2) && defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX__)
#define ALOHA_BLEND_AVX 1
#define ALOHA_KERNEL inline __attribute__((always_inline))
#else
#define ALOHA_KERNEL inline
#endif

namespace aloha {

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "blend_rest_x4 reads glm::vec3 as three packed floats");

void blend_rest(std::span<const glm::vec3> muscle_positions, std::span<const glm::vec3> muscle_normals, uint32_t grid_vertices,
                const BlendBinding& b, glm::vec3& root, glm::vec3& rest) {
    const size_t V = grid_vertices;
    root = glm::vec3(0.0f);
    rest = glm::vec3(0.0f);
    for (int k = 0; k < kBlendInfluences; ++k) {
        if (b.weight[k] <= 0.0f) continue;
        const size_t base = size_t{b.muscle[k]} * V;
        const GridFrame f = sample_grid_frame(muscle_positions.subspan(base, V), muscle_normals.subspan(base, V), b.cell[k]);
        root += b.weight[k] * f.point;
        rest += b.weight[k] * (f.point + b.offset[k].x * f.tangent + b.offset[k].y * f.bitangent + b.offset[k].z * f.normal);
    }
}

#ifdef ALOHA_BLEND_SSE2
namespace {

// Four vec3s, one per lane.
struct Lanes3 {
    __m128 x, y, z;
};

// The vec3 at p as (x, y, z, 0), reading only its twelve bytes.
inline __m128 load3(const glm::vec3* p) {
    const __m128 xy = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
    return _mm_movelh_ps(xy, _mm_load_ss(&p->z));
}

// The vec3 `bytes` past `base`, as load3().
inline __m128 load3(const glm::vec3* base, uint32_t bytes) {
    return load3(reinterpret_cast<const glm::vec3*>(reinterpret_cast<const char*>(base) + bytes));
}

// Lanes of four vec3s loaded as (x, y, z, any): the x, y, z rows of their 4x4 transpose.
inline Lanes3 transpose(__m128 a, __m128 b, __m128 c, __m128 d) {
    const __m128 lo_ab = _mm_unpacklo_ps(a, b), lo_cd = _mm_unpacklo_ps(c, d);  // ax bx ay by | cx dx cy dy
    const __m128 hi_ab = _mm_unpackhi_ps(a, b), hi_cd = _mm_unpackhi_ps(c, d);  // az bz .. .. | cz dz .. ..
    return {_mm_movelh_ps(lo_ab, lo_cd), _mm_movehl_ps(lo_cd, lo_ab), _mm_movelh_ps(hi_ab, hi_cd)};
}

// Lanes of the vec3s at byte offsets at[lane][corner] past base.
inline Lanes3 gather(const glm::vec3* base, const uint32_t at[4][4], int corner) {
    return transpose(load3(base, at[0][corner]), load3(base, at[1][corner]), load3(base, at[2][corner]),
                     load3(base, at[3][corner]));
}

inline Lanes3 add(Lanes3 a, Lanes3 b) { return {_mm_add_ps(a.x, b.x), _mm_add_ps(a.y, b.y), _mm_add_ps(a.z, b.z)}; }
inline Lanes3 sub(Lanes3 a, Lanes3 b) { return {_mm_sub_ps(a.x, b.x), _mm_sub_ps(a.y, b.y), _mm_sub_ps(a.z, b.z)}; }
inline Lanes3 mul(Lanes3 a, __m128 s) { return {_mm_mul_ps(a.x, s), _mm_mul_ps(a.y, s), _mm_mul_ps(a.z, s)}; }
inline Lanes3 div(Lanes3 a, __m128 s) { return {_mm_div_ps(a.x, s), _mm_div_ps(a.y, s), _mm_div_ps(a.z, s)}; }
// glm::dot: products summed x + y, then + z.
inline __m128 dot(Lanes3 a, Lanes3 b) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a.x, b.x), _mm_mul_ps(a.y, b.y)), _mm_mul_ps(a.z, b.z));
}
// glm::mix with a scalar fraction: x (1 - a) + y a (one_minus_a = 1 - a, as glm computes it).
inline Lanes3 mix(Lanes3 x, Lanes3 y, __m128 one_minus_a, __m128 a) { return add(mul(x, one_minus_a), mul(y, a)); }
// glm::cross(a, b).
inline Lanes3 cross(Lanes3 a, Lanes3 b) {
    return {_mm_sub_ps(_mm_mul_ps(a.y, b.z), _mm_mul_ps(b.y, a.z)), _mm_sub_ps(_mm_mul_ps(a.z, b.x), _mm_mul_ps(b.z, a.x)),
            _mm_sub_ps(_mm_mul_ps(a.x, b.y), _mm_mul_ps(b.x, a.y))};
}
// Per lane: `on` ? a : b.
inline Lanes3 select(__m128 on, Lanes3 a, Lanes3 b) {
    auto pick = [on](__m128 u, __m128 v) { return _mm_or_ps(_mm_and_ps(on, u), _mm_andnot_ps(on, v)); };
    return {pick(a.x, b.x), pick(a.y, b.y), pick(a.z, b.z)};
}

// blend_rest_x4() in the instruction set of the function it is inlined into.
ALOHA_KERNEL bool rest_x4(std::span<const glm::vec3> muscle_positions, std::span<const glm::vec3> muscle_normals,
                          uint32_t grid_vertices, const BlendBinding* b, float root[3][4], float rest[3][4]) {
    const glm::vec3* const positions = muscle_positions.data();
    const glm::vec3* const normals = muscle_normals.data();
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
    const __m128 min_normal = _mm_set1_ps(1e-20f), min_tangent = _mm_set1_ps(1e-12f);  // sample_grid_frame's
    Lanes3 r{zero, zero, zero}, y{zero, zero, zero};
    for (int k = 0; k < kBlendInfluences; ++k) {
        const __m128 w = _mm_setr_ps(b[0].weight[k], b[1].weight[k], b[2].weight[k], b[3].weight[k]);
        const __m128 on = _mm_cmpnle_ps(w, zero);  // !(w <= 0): the scalar form's skip, NaN included
        const int active = _mm_movemask_ps(on);
        if (active == 0) continue;
        // Byte offsets of the cell corners in both spans, (muscle V + corner) 12, per lane; an inactive lane reads
        // vertex 0 of muscle 0 and is discarded.
        alignas(16) uint32_t at[4][4];
        for (int lane = 0; lane < 4; ++lane) {
            __m128i index = _mm_setzero_si128();
            if ((active >> lane & 1) != 0)
                index = _mm_add_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(b[lane].cell[k].corner)),
                                      _mm_set1_epi32(static_cast<int>(b[lane].muscle[k] * grid_vertices)));
            _mm_store_si128(reinterpret_cast<__m128i*>(at[lane]),
                            _mm_add_epi32(_mm_slli_epi32(index, 3), _mm_slli_epi32(index, 2)));
        }
        const __m128 ft = _mm_setr_ps(b[0].cell[k].ft, b[1].cell[k].ft, b[2].cell[k].ft, b[3].cell[k].ft);
        const __m128 fr = _mm_setr_ps(b[0].cell[k].fr, b[1].cell[k].fr, b[2].cell[k].fr, b[3].cell[k].fr);
        const __m128 ft1 = _mm_sub_ps(one, ft), fr1 = _mm_sub_ps(one, fr);
        // sample_grid_frame(), lane by lane.
        const Lanes3 p00 = gather(positions, at, 0), p01 = gather(positions, at, 1);
        const Lanes3 p10 = gather(positions, at, 2), p11 = gather(positions, at, 3);
        const Lanes3 point = mix(mix(p00, p01, ft1, ft), mix(p10, p11, ft1, ft), fr1, fr);
        const Lanes3 n = mix(mix(gather(normals, at, 0), gather(normals, at, 1), ft1, ft),
                             mix(gather(normals, at, 2), gather(normals, at, 3), ft1, ft), fr1, fr);
        const __m128 nlen = _mm_sqrt_ps(dot(n, n));
        const Lanes3 normal = div(n, nlen);
        Lanes3 tangent = mix(sub(p01, p00), sub(p11, p10), fr1, fr);
        tangent = sub(tangent, mul(normal, dot(tangent, normal)));
        const __m128 tlen = _mm_sqrt_ps(dot(tangent, tangent));
        // Where the scalar form takes a fallback direction, it decides these vertices.
        const __m128 regular = _mm_and_ps(_mm_cmpgt_ps(nlen, min_normal), _mm_cmpgt_ps(tlen, min_tangent));
        if ((_mm_movemask_ps(regular) & active) != active) return false;
        const Lanes3 t = div(tangent, tlen);
        const Lanes3 bt = cross(normal, t);
        // root += w P; rest += w (((P + ox t) + oy b) + oz n), skipped (not + 0) where w <= 0.
        const __m128 ox = _mm_setr_ps(b[0].offset[k].x, b[1].offset[k].x, b[2].offset[k].x, b[3].offset[k].x);
        const __m128 oy = _mm_setr_ps(b[0].offset[k].y, b[1].offset[k].y, b[2].offset[k].y, b[3].offset[k].y);
        const __m128 oz = _mm_setr_ps(b[0].offset[k].z, b[1].offset[k].z, b[2].offset[k].z, b[3].offset[k].z);
        const Lanes3 end = add(add(add(point, mul(t, ox)), mul(bt, oy)), mul(normal, oz));
        r = select(on, add(r, mul(point, w)), r);
        y = select(on, add(y, mul(end, w)), y);
    }
    _mm_storeu_ps(root[0], r.x);
    _mm_storeu_ps(root[1], r.y);
    _mm_storeu_ps(root[2], r.z);
    _mm_storeu_ps(rest[0], y.x);
    _mm_storeu_ps(rest[1], y.y);
    _mm_storeu_ps(rest[2], y.z);
    return true;
}

// Lanes of the four consecutive vec3s at p (reading only their 48 bytes).
inline Lanes3 load4(const glm::vec3* p) {
    return transpose(_mm_loadu_ps(&p[0].x), _mm_loadu_ps(&p[1].x), _mm_loadu_ps(&p[2].x), load3(p + 3));  // 3 x 16 + 12 bytes
}

// Writes the lanes as the four consecutive vec3s at p (only their 48 bytes).
inline void store4(Lanes3 v, glm::vec3* p) {
    const __m128 xy01 = _mm_unpacklo_ps(v.x, v.y), xy23 = _mm_unpackhi_ps(v.x, v.y);  // x0 y0 x1 y1 | x2 y2 x3 y3
    _mm_storel_pi(reinterpret_cast<__m64*>(&p[0].x), xy01);
    _mm_storeh_pi(reinterpret_cast<__m64*>(&p[1].x), xy01);
    _mm_storel_pi(reinterpret_cast<__m64*>(&p[2].x), xy23);
    _mm_storeh_pi(reinterpret_cast<__m64*>(&p[3].x), xy23);
    _mm_store_ss(&p[0].z, v.z);
    _mm_store_ss(&p[1].z, _mm_shuffle_ps(v.z, v.z, _MM_SHUFFLE(1, 1, 1, 1)));
    _mm_store_ss(&p[2].z, _mm_shuffle_ps(v.z, v.z, _MM_SHUFFLE(2, 2, 2, 2)));
    _mm_store_ss(&p[3].z, _mm_shuffle_ps(v.z, v.z, _MM_SHUFFLE(3, 3, 3, 3)));
}

inline Lanes3 rows(const float v[3][4]) { return {_mm_loadu_ps(v[0]), _mm_loadu_ps(v[1]), _mm_loadu_ps(v[2])}; }

// Per lane: all of v's components finite (x * 0 is 0 exactly for finite x, NaN for inf and NaN).
inline __m128 finite(Lanes3 v) {
    const __m128 zero = _mm_setzero_ps();
    return _mm_and_ps(_mm_and_ps(_mm_cmpeq_ps(_mm_mul_ps(v.x, zero), zero), _mm_cmpeq_ps(_mm_mul_ps(v.y, zero), zero)),
                      _mm_cmpeq_ps(_mm_mul_ps(v.z, zero), zero));
}

// spring_step_x4() in the instruction set of the function it is inlined into.
ALOHA_KERNEL void step_x4(const float root[3][4], const float rest[3][4], const SpringStepper* const steppers[4], glm::vec3* end,
                          glm::vec3* velocity, glm::vec3* prev_rest) {
    const SpringStepper &s0 = *steppers[0], &s1 = *steppers[1], &s2 = *steppers[2], &s3 = *steppers[3];
    auto lanes = [&](float SpringStepper::*f) { return _mm_setr_ps(s0.*f, s1.*f, s2.*f, s3.*f); };
    auto lanes_of = [&](SpringTransition SpringStepper::*t, float SpringTransition::*f) {
        return _mm_setr_ps(s0.*t.*f, s1.*t.*f, s2.*t.*f, s3.*t.*f);
    };
    const __m128 zero = _mm_setzero_ps();
    const Lanes3 y = rows(rest);
    // The spring's axis: normal (rest - root) / h, +z where h <= 1e-6 (BlendSpringJob).
    const Lanes3 axis = sub(y, rows(root));
    const __m128 h = _mm_sqrt_ps(dot(axis, axis));
    const Lanes3 n = select(_mm_cmpgt_ps(h, _mm_set1_ps(1e-6f)), div(axis, h), Lanes3{zero, zero, _mm_set1_ps(1.0f)});
    // SpringStepper::step().
    const __m128 max_dev = _mm_mul_ps(lanes(&SpringStepper::max_strain), h);
    const __m128 max_rate = _mm_mul_ps(max_dev, lanes(&SpringStepper::normal_omega));
    const Lanes3 prev = load4(prev_rest);
    const Lanes3 w = mul(sub(y, prev), lanes(&SpringStepper::inv_dt));
    const Lanes3 d0 = sub(load4(end), prev);
    const Lanes3 u0 = sub(load4(velocity), w);
    const __m128 dn = dot(d0, n), un = dot(u0, n);
    const Lanes3 dl = sub(d0, mul(n, dn)), ul = sub(u0, mul(n, un));
    using S = SpringStepper;
    using Tr = SpringTransition;
    const __m128 dn1 = _mm_add_ps(_mm_mul_ps(lanes_of(&S::normal, &Tr::a), dn), _mm_mul_ps(lanes_of(&S::normal, &Tr::b), un));
    const __m128 un1 = _mm_add_ps(_mm_mul_ps(lanes_of(&S::normal, &Tr::c), dn), _mm_mul_ps(lanes_of(&S::normal, &Tr::e), un));
    Lanes3 d1 = add(add(mul(n, dn1), mul(dl, lanes_of(&S::lateral, &Tr::a))), mul(ul, lanes_of(&S::lateral, &Tr::b)));
    Lanes3 u1 = add(add(mul(n, un1), mul(dl, lanes_of(&S::lateral, &Tr::c))), mul(ul, lanes_of(&S::lateral, &Tr::e)));
    // Strain limiting: onto the ball |d| <= max_dev, outward relative velocity removed.
    const __m128 dlen2 = dot(d1, d1);
    const __m128 limit = _mm_cmpgt_ps(dlen2, _mm_mul_ps(max_dev, max_dev));
    const Lanes3 dir = div(d1, _mm_sqrt_ps(dlen2));
    const __m128 outward = dot(u1, dir);
    u1 = select(_mm_and_ps(limit, _mm_cmpgt_ps(outward, zero)), sub(u1, mul(dir, outward)), u1);
    d1 = select(limit, mul(dir, max_dev), d1);
    const __m128 ulen2 = dot(u1, u1);
    u1 = select(_mm_cmpgt_ps(ulen2, _mm_mul_ps(max_rate, max_rate)), mul(u1, _mm_div_ps(max_rate, _mm_sqrt_ps(ulen2))), u1);
    // Non-finite: restart at rest.
    const __m128 ok = _mm_and_ps(finite(d1), finite(u1));
    const Lanes3 still{zero, zero, zero};
    d1 = select(ok, d1, still);
    u1 = select(ok, u1, still);
    store4(add(y, d1), end);
    store4(add(w, u1), velocity);
    store4(y, prev_rest);
}

#ifdef ALOHA_BLEND_AVX
__attribute__((target("avx"))) bool rest_x4_avx(std::span<const glm::vec3> muscle_positions,
                                                std::span<const glm::vec3> muscle_normals, uint32_t grid_vertices,
                                                const BlendBinding* b, float root[3][4], float rest[3][4]) {
    return rest_x4(muscle_positions, muscle_normals, grid_vertices, b, root, rest);
}

__attribute__((target("avx"))) void step_x4_avx(const float root[3][4], const float rest[3][4],
                                                const SpringStepper* const steppers[4], glm::vec3* end, glm::vec3* velocity,
                                                glm::vec3* prev_rest) {
    step_x4(root, rest, steppers, end, velocity, prev_rest);
}

// The CPU and the operating system run AVX (checked once).
bool use_avx() {
    static const bool avx = __builtin_cpu_supports("avx");
    return avx;
}
#endif

}  // namespace

bool blend_rest_x4(std::span<const glm::vec3> muscle_positions, std::span<const glm::vec3> muscle_normals, uint32_t grid_vertices,
                   const BlendBinding* b, float root[3][4], float rest[3][4], bool allow_avx) {
#ifdef ALOHA_BLEND_AVX
    if (allow_avx && use_avx()) return rest_x4_avx(muscle_positions, muscle_normals, grid_vertices, b, root, rest);
#else
    (void)allow_avx;
#endif
    return rest_x4(muscle_positions, muscle_normals, grid_vertices, b, root, rest);
}

void spring_step_x4(const float root[3][4], const float rest[3][4], const SpringStepper* const steppers[4], glm::vec3* end,
                    glm::vec3* velocity, glm::vec3* prev_rest, bool allow_avx) {
#ifdef ALOHA_BLEND_AVX
    if (allow_avx && use_avx()) return step_x4_avx(root, rest, steppers, end, velocity, prev_rest);
#else
    (void)allow_avx;
#endif
    step_x4(root, rest, steppers, end, velocity, prev_rest);
}

#else

void spring_step_x4(const float root[3][4], const float rest[3][4], const SpringStepper* const steppers[4], glm::vec3* end,
                    glm::vec3* velocity, glm::vec3* prev_rest, bool) {
    for (int lane = 0; lane < 4; ++lane) {
        const glm::vec3 r{root[0][lane], root[1][lane], root[2][lane]}, y{rest[0][lane], rest[1][lane], rest[2][lane]};
        const glm::vec3 axis = y - r;
        const float h = glm::length(axis);
        const glm::vec3 n = h > 1e-6f ? axis / h : glm::vec3(0.0f, 0.0f, 1.0f);
        steppers[lane]->step(y, n, h, end[lane], velocity[lane], prev_rest[lane]);
    }
}

bool blend_rest_x4(std::span<const glm::vec3>, std::span<const glm::vec3>, uint32_t, const BlendBinding*, float[3][4],
                   float[3][4], bool) {
    return false;
}

#endif

}  // namespace aloha
