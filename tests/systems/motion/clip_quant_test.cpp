// Quantised clips (ClipEncoding::Quantized16): every key and random times sample within the clip's
// derived error bound of the float source (clip_quant.hpp), model positions within the bound that
// bound implies along each joint chain, the documented format sizes, constant tracks stored once,
// and the SIMD decode paths bit-identical to the scalar formulas.
#include "systems/motion/clip.hpp"
#include "systems/motion/clip_quant.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/sampling.hpp"
#include "tests/systems/motion/clip_reference.hpp"
#include "tests/systems/motion/motion_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

namespace aloha {
namespace {

Skeleton humanoid() { return build_skeleton(test::make_humanoid64(), "humanoid64").value(); }
Skeleton chain(int n) { return build_skeleton(test::make_chain(n), "chain").value(); }

struct Pose {
    explicit Pose(int n) : t(static_cast<size_t>(n)), r(static_cast<size_t>(n)), s(static_cast<size_t>(n)) {}
    std::vector<glm::vec3> t;
    std::vector<glm::quat> r;
    std::vector<glm::vec3> s;
};

// Largest sampling errors seen (same units as ClipErrorBound).
struct Seen {
    double t = 0.0, r = 0.0, s = 0.0;
};

// Compares a sampled pose with the source at time `time` against the clip's bound; records the worst.
void expect_within_bound(const AnimationClip& clip, const RawAnimation& raw, const Skeleton& sk, const Pose& p,
                         double time, Seen* seen) {
    const test::RefPose ref = test::ref_pose(raw, sk, time);
    const ClipErrorBound& b = clip.error_bound();
    for (size_t j = 0; j < p.t.size(); ++j) {
        for (int c = 0; c < 3; ++c) {
            const double et = std::abs(static_cast<double>(p.t[j][c]) - ref.t[j][c]);
            const double es = std::abs(static_cast<double>(p.s[j][c]) - ref.s[j][c]);
            EXPECT_LE(et, b.translation) << clip.name() << " joint " << j << " t=" << time;
            EXPECT_LE(es, b.scale) << clip.name() << " joint " << j << " t=" << time;
            seen->t = std::max(seen->t, et);
            seen->s = std::max(seen->s, es);
        }
        const double er = test::rotation_angle(p.r[j], ref.r[j]);
        EXPECT_LE(er, b.rotation) << clip.name() << " joint " << j << " t=" << time;
        seen->r = std::max(seen->r, er);
    }
}

// Samples every key (and the end of the last segment) and `random_times` random times.
Seen check_clip(const RawAnimation& raw, const Skeleton& sk, ClipEncoding encoding, int random_times) {
    const AnimationClip clip = build_clip(raw, sk, encoding).value();
    const ClipErrorBound& b = clip.error_bound();
    std::printf("[ bound ] %s %s: translation %.3g, rotation %.3g rad, scale %.3g\n", clip.name().c_str(),
                encoding == ClipEncoding::Quantized16 ? "q16" : "f32", b.translation, b.rotation, b.scale);
    Pose p(sk.joint_count());
    Seen seen;
    for (int k = 0; k < clip.key_count(); ++k) {
        sample_blocks(clip, k, 0.0f, p.t.data(), p.r.data(), p.s.data());
        expect_within_bound(clip, raw, sk, p, clip.times()[static_cast<size_t>(k)], &seen);
    }
    if (clip.key_count() > 1) {
        sample_blocks(clip, clip.key_count() - 2, 1.0f, p.t.data(), p.r.data(), p.s.data());
        expect_within_bound(clip, raw, sk, p, clip.duration(), &seen);
    }
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> u(0.0f, clip.duration());
    for (int i = 0; i < random_times; ++i) {
        const float t = u(rng);
        SampleJob job{&clip, t, false, nullptr, p.t, p.r, p.s};
        job.Run();
        int k = 0;
        float alpha = 0.0f;
        find_key(clip, t, nullptr, &k, &alpha);  // the segment the job used: reference at the same point
        expect_within_bound(clip, raw, sk, p, test::segment_time(clip, k, alpha), &seen);
    }
    return seen;
}

// Large rotations about a wandering axis (components over most of [-1, 1]), metre translations and
// non-uniform scales: exercises the bound far from the benchmark clip's small ranges.
RawAnimation wide_clip(const Skeleton& sk, int keys, float duration) {
    RawAnimation a;
    a.name = "wide";
    a.duration = duration;
    a.tracks.resize(static_cast<size_t>(sk.joint_count()));
    for (size_t j = 0; j < a.tracks.size(); ++j) {
        RawJointTracks& tr = a.tracks[j];
        for (int k = 0; k < keys; ++k) {
            const float t = duration * static_cast<float>(k) / static_cast<float>(keys - 1);
            const float ph = 6.2831853f * t / duration + 0.7f * static_cast<float>(j);
            const glm::vec3 axis = glm::normalize(glm::vec3(std::cos(2.0f * ph), std::sin(2.0f * ph), 0.3f));
            tr.translations.times.push_back(t);
            tr.translations.values.push_back(glm::vec3(2.0f * std::sin(ph), 0.5f * std::cos(ph), -1.0f + std::sin(3.0f * ph)));
            tr.rotations.times.push_back(t);
            tr.rotations.values.push_back(glm::angleAxis(3.0f * std::sin(ph), axis));
            tr.scales.times.push_back(t);
            tr.scales.values.push_back(glm::vec3(1.0f + 0.5f * std::sin(ph), 1.0f, 0.8f + 0.1f * std::cos(ph)));
        }
    }
    return a;
}

// Tracks with their own random key times (the union timeline inserts chord keys) and random values,
// rotations random unit quaternions (consecutive keys up to 90 degrees apart after alignment).
RawAnimation random_timeline_clip(const Skeleton& sk) {
    RawAnimation a;
    a.name = "random_timeline";
    a.tracks.resize(static_cast<size_t>(sk.joint_count()));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto make_times = [&](int count) {
        std::vector<float> times{0.0f};
        for (int i = 1; i < count; ++i) times.push_back(times.back() + 0.02f + 0.2f * (u(rng) + 1.0f));
        return times;
    };
    for (RawJointTracks& tr : a.tracks) {
        tr.translations.times = make_times(7);
        for (size_t i = 0; i < tr.translations.times.size(); ++i) tr.translations.values.push_back({u(rng), u(rng), u(rng)});
        tr.rotations.times = make_times(9);
        for (size_t i = 0; i < tr.rotations.times.size(); ++i)
            tr.rotations.values.push_back(glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng))));
        tr.scales.times = make_times(4);
        for (size_t i = 0; i < tr.scales.times.size(); ++i)
            tr.scales.values.push_back({1.0f + 0.3f * u(rng), 1.0f + 0.3f * u(rng), 1.0f + 0.3f * u(rng)});
    }
    return a;
}

TEST(QuantisedClip, EveryKeyAndRandomTimesWithinBound) {
    const Skeleton h = humanoid(), c4 = chain(4), c5 = chain(5);
    const RawAnimation bench = test::make_wave_clip(h, 61, 2.0f);
    for (ClipEncoding e : {ClipEncoding::Quantized16, ClipEncoding::Float32}) {
        const Seen a = check_clip(bench, h, e, 200);
        const Seen b = check_clip(wide_clip(c5, 41, 2.0f), c5, e, 300);
        const Seen c = check_clip(random_timeline_clip(c4), c4, e, 500);
        std::printf("[ %s ] max error (bench / wide / random timeline): translation %.3g / %.3g / %.3g, "
                    "rotation %.3g / %.3g / %.3g rad, scale %.3g / %.3g / %.3g\n",
                    e == ClipEncoding::Quantized16 ? "q16" : "f32", a.t, b.t, c.t, a.r, b.r, c.r, a.s, b.s, c.s);
    }
}

TEST(QuantisedClip, BoundFollowsTheFormat) {
    const Skeleton h = humanoid();
    const RawAnimation raw = test::make_wave_clip(h, 61, 2.0f);
    const AnimationClip q = build_clip(raw, h).value();
    const AnimationClip f = build_clip(raw, h, ClipEncoding::Float32).value();
    EXPECT_EQ(q.encoding(), ClipEncoding::Quantized16);  // the default
    // Translation bound from the source keys alone: the widest channel's step / 2 + float slack.
    double expect_t = 0.0;
    for (const RawJointTracks& tr : raw.tracks)
        for (int c = 0; c < 3; ++c) {
            float lo = tr.translations.values[0][c], hi = lo;
            for (const glm::vec3& v : tr.translations.values) { lo = std::min(lo, v[c]); hi = std::max(hi, v[c]); }
            const double ext = static_cast<double>(hi) - lo;
            const double m = std::max(std::abs(static_cast<double>(lo)), std::abs(static_cast<double>(hi)));
            expect_t = std::max(expect_t, ext / 65535.0 / 2.0 + std::ldexp(ext + m, -21));
        }
    EXPECT_NEAR(q.error_bound().translation, expect_t, 1e-6 * expect_t);
    // No clip's rotation bound exceeds the worst case (every component over [-1, 1]):
    // step 2/65535, b = step/2 + 3 * 2^-21, |e| <= 2b, angle <= 2 asin(sqrt(2) 2b) + 2^-20 ~ 9.5e-5 rad.
    const double b = 1.0 / 65535.0 + 3.0 * std::ldexp(1.0, -21);
    const double worst = 2.0 * std::asin(std::sqrt(2.0) * 2.0 * b) + std::ldexp(1.0, -20);
    EXPECT_LT(worst, 9.6e-5);
    const Skeleton c5 = chain(5);
    const AnimationClip wide = build_clip(wide_clip(c5, 41, 2.0f), c5).value();
    EXPECT_LE(wide.error_bound().rotation, worst);
    EXPECT_GT(wide.error_bound().rotation, 0.5 * worst);  // the wide clip nearly reaches it
    EXPECT_LE(q.error_bound().rotation, worst);
    // Float32 clips carry float rounding only: 2^-21 (ext + M) per component (~1e-6 at most for
    // unit quaternions, E < 1e-6 over four), so 2 sqrt(2) E + 2^-20 < 4e-6 rad.
    EXPECT_LT(f.error_bound().translation, 2e-6f);
    EXPECT_LT(f.error_bound().rotation, 4e-6f);
    EXPECT_LT(q.error_bound().translation, 1e-6f);  // benchmark clip: +-1 cm waves on < 1.1 m offsets
}

TEST(QuantisedClip, ModelPositionsWithinChainBound) {
    // Model position error of joint j, telescoping over its chain root..j: fixing joint i's local
    // transform (dt, R', S') moves j by M'_parent(i) [dt + (R'S' - RS) x], x = j in i's frame, so
    //   |dp_j| <= sum_i G'_p(i) (sqrt(3) e_t + (e_r (smax_i + e_s) + e_s) |p_j - p_i| / g_i)
    // with G' the product of the chain's largest scales (+ e_s) above i, g_i the product of the
    // smallest scales down to i (|x| <= |p_j - p_i| / g_i) and e_t, e_r, e_s the clip's bound.
    // Float local-to-model adds <= 8 roundings (2^-21) per level to each matrix column: a joint at
    // depth d gets 2^-20 sum_i (d_i G'_p(i) |t_i| + |p_i|) (2x margin).
    const Skeleton sk = humanoid();
    const RawAnimation raw = test::make_wave_clip(sk, 61, 2.0f);
    const AnimationClip clip = build_clip(raw, sk).value();
    const ClipErrorBound& e = clip.error_bound();
    const size_t n = static_cast<size_t>(sk.joint_count());
    Pose p(sk.joint_count());
    std::vector<glm::mat4> model(n);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, clip.duration());
    double worst_seen = 0.0, worst_bound = 0.0;
    for (int i = 0; i < 121; ++i) {
        const float t = i < 61 ? clip.times()[static_cast<size_t>(i)] : u(rng);
        int k = 0;
        float alpha = 0.0f;
        find_key(clip, t, nullptr, &k, &alpha);
        sample_blocks(clip, k, alpha, p.t.data(), p.r.data(), p.s.data());
        LocalToModelJob{sk.parents(), p.t, p.r, p.s, nullptr, model}.Run();
        const test::RefPose ref = test::ref_pose(raw, sk, test::segment_time(clip, k, alpha));
        const std::vector<glm::dmat4> exact = test::ref_model(ref, sk);
        std::vector<double> gmax(n), gmin(n);  // G' and g down to each joint
        std::vector<int> depth(n);
        for (size_t j = 0; j < n; ++j) {
            const int par = sk.parents()[j];
            const double smax = std::max({ref.s[j].x, ref.s[j].y, ref.s[j].z});
            const double smin = std::min({ref.s[j].x, ref.s[j].y, ref.s[j].z});
            gmax[j] = (par < 0 ? 1.0 : gmax[static_cast<size_t>(par)]) * (smax + e.scale);
            gmin[j] = (par < 0 ? 1.0 : gmin[static_cast<size_t>(par)]) * smin;
            depth[j] = par < 0 ? 1 : depth[static_cast<size_t>(par)] + 1;
        }
        for (size_t j = 0; j < n; ++j) {
            const glm::dvec3 pj(exact[j][3]);
            double bound = 0.0, slack = 0.0;
            for (int a = static_cast<int>(j); a >= 0; a = sk.parents()[static_cast<size_t>(a)]) {
                const size_t ai = static_cast<size_t>(a);
                const int par = sk.parents()[ai];
                const double gp = par < 0 ? 1.0 : gmax[static_cast<size_t>(par)];
                const double smax = std::max({ref.s[ai].x, ref.s[ai].y, ref.s[ai].z});
                const double r = glm::length(pj - glm::dvec3(exact[ai][3]));
                bound += gp * (std::sqrt(3.0) * e.translation + (e.rotation * (smax + e.scale) + e.scale) * r / gmin[ai]);
                slack += depth[ai] * gp * glm::length(ref.t[ai]) + glm::length(glm::dvec3(exact[ai][3]));
            }
            bound += std::ldexp(slack, -20);
            const double err = glm::length(glm::dvec3(glm::vec3(model[j][3])) - pj);
            EXPECT_LE(err, bound) << "joint " << j << " t=" << t;
            worst_seen = std::max(worst_seen, err);
            worst_bound = std::max(worst_bound, bound);
        }
    }
    std::printf("[ q16 ] model position error: max %.3g m, largest bound %.3g m\n", worst_seen, worst_bound);
    EXPECT_LT(worst_bound, 1e-3);  // the bound itself: under a millimetre on a 1.7 m figure
}

TEST(QuantisedClip, BenchmarkClipSizes) {
    // motion_bench's clip: 64 joints, 61 uniform keys, T/R/S animated on every joint. Blocks hold
    // 640 values; quantised: 2 bytes each plus 8 bytes of range per value; times 61 floats.
    const Skeleton sk = humanoid();
    const RawAnimation raw = test::make_wave_clip(sk, 61, 2.0f);
    const AnimationClip q = build_clip(raw, sk).value();
    const AnimationClip f = build_clip(raw, sk, ClipEncoding::Float32).value();
    EXPECT_EQ(q.block_elements(), 640u);
    EXPECT_EQ(q.byte_size(), 61u * 640u * 2u + 640u * 8u + 61u * 4u);  // 83,444
    EXPECT_LE(q.byte_size(), 105956u);                                 // ozz-animation 0.16, same clip
    EXPECT_EQ(f.byte_size(), 61u * 640u * 4u + 61u * 4u);              // 156,404: the float layout
}

TEST(QuantisedClip, ConstantTracksAreStoredOnce) {
    // The motion library's shape: rotations on every joint, translation on the root only, no scales.
    const Skeleton sk = chain(10);
    RawAnimation raw;
    raw.name = "library_like";
    raw.tracks.resize(10);
    for (int k = 0; k < 31; ++k) {
        const float t = static_cast<float>(k) / 30.0f;
        raw.tracks[0].translations.times.push_back(t);
        raw.tracks[0].translations.values.push_back(glm::vec3(1.4f * t, 0.9f + 0.02f * std::sin(6.28f * t), 0.0f));
        for (size_t j = 0; j < 10; ++j) {
            raw.tracks[j].rotations.times.push_back(t);
            raw.tracks[j].rotations.values.push_back(glm::angleAxis(0.3f * std::sin(6.28f * t + static_cast<float>(j)),
                                                                    glm::vec3(1, 0, 0)));
        }
    }
    const AnimationClip clip = build_clip(raw, sk).value();
    EXPECT_EQ(clip.section(AnimationClip::kTranslations).first, 0);
    EXPECT_EQ(clip.section(AnimationClip::kTranslations).count, 1);
    EXPECT_EQ(clip.section(AnimationClip::kRotations).count, 10);
    EXPECT_EQ(clip.section(AnimationClip::kScales).count, 0);
    const size_t block = 3 + 4 * 10;
    EXPECT_EQ(clip.block_elements(), block);
    // Keys + ranges + times + the constant translations and scales of all 10 joints, once.
    EXPECT_EQ(clip.byte_size(), 31 * block * 2 + block * 8 + 31 * 4 + 10 * 12 * 2);
    Pose p(10);
    for (float t : {0.0f, 0.37f, 1.0f}) {
        SampleJob{&clip, t, false, nullptr, p.t, p.r, p.s}.Run();
        for (size_t j = 0; j < 10; ++j) {
            EXPECT_EQ(p.s[j], sk.rest_scales()[j]);  // constants are copied bit for bit
            if (j > 0) {
                EXPECT_EQ(p.t[j], sk.rest_translations()[j]);
            }
        }
    }
    Seen seen;
    for (float t : {0.0f, 0.51f, 1.0f}) {
        int k = 0;
        float alpha = 0.0f;
        find_key(clip, t, nullptr, &k, &alpha);
        sample_blocks(clip, k, alpha, p.t.data(), p.r.data(), p.s.data());
        expect_within_bound(clip, raw, sk, p, test::segment_time(clip, k, alpha), &seen);
    }
}

TEST(QuantisedClip, VectorLanesMatchTheScalarTail) {
    // Five joints with identical tracks: joints 0-3 decode in SIMD lanes, joint 4 (and the last
    // translation / scale values) in the scalar tail; both must give the same bits.
    const Skeleton sk = chain(5);
    RawAnimation raw = wide_clip(sk, 21, 1.0f);
    for (size_t j = 1; j < 5; ++j) raw.tracks[j] = raw.tracks[0];
    for (ClipEncoding e : {ClipEncoding::Quantized16, ClipEncoding::Float32}) {
        const AnimationClip clip = build_clip(raw, sk, e).value();
        Pose p(5);
        for (float t : {0.0f, 0.013f, 0.5f, 0.77f, 1.0f}) {
            SampleJob{&clip, t, false, nullptr, p.t, p.r, p.s}.Run();
            for (size_t j = 1; j < 5; ++j) {
                EXPECT_EQ(p.t[j], p.t[0]);
                EXPECT_EQ(p.r[j], p.r[0]);
                EXPECT_EQ(p.s[j], p.s[0]);
            }
        }
    }
}

TEST(QuantisedClip, DecodePathsGiveTheSameBits) {
    // The kernels with AVX2 allowed (8 lanes where the CPU has it, then 4, then scalar) and not
    // (4 lanes, then scalar) against the scalar formulas written out here: bit for bit. 23 joints
    // and 69 values leave work for every path (16 + 4 + 3 rotations, 64 + 4 + 1 values).
    const size_t joints = 23, values = 3 * joints, planes = 4 * joints;
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> code(0, 65535);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<uint16_t> qa(planes), qb(planes);
    std::vector<float> fa(planes), fb(planes), base(planes), step(planes);
    for (size_t i = 0; i < planes; ++i) {
        qa[i] = static_cast<uint16_t>(code(rng));
        qb[i] = static_cast<uint16_t>(code(rng));
        fa[i] = u(rng);
        fb[i] = u(rng);
        base[i] = u(rng);
        step[i] = 2.0f * (u(rng) + 1.0f) / 65535.0f;
    }
    const float wb = 0.3731f, wa = 1.0f - wb;
    std::printf("[ simd ] AVX2 %s\n", clip_simd::avx2_available() ? "used" : "not available: SSE2 and scalar only");
    auto same = [](const void* x, const void* y, size_t bytes) { return std::memcmp(x, y, bytes) == 0; };
    std::vector<float> want(values), got(values), got4(values);
    for (size_t i = 0; i < values; ++i) want[i] = base[i] + step[i] * (wa * static_cast<float>(qa[i]) + wb * static_cast<float>(qb[i]));
    decode_lerp(qa.data(), qb.data(), base.data(), step.data(), wa, wb, got.data(), values, true);
    decode_lerp(qa.data(), qb.data(), base.data(), step.data(), wa, wb, got4.data(), values, false);
    EXPECT_TRUE(same(got.data(), want.data(), values * sizeof(float)));
    EXPECT_TRUE(same(got4.data(), want.data(), values * sizeof(float)));
    for (size_t i = 0; i < values; ++i) want[i] = fa[i] * wa + fb[i] * wb;
    decode_lerp(fa.data(), fb.data(), wa, wb, got.data(), values, true);
    decode_lerp(fa.data(), fb.data(), wa, wb, got4.data(), values, false);
    EXPECT_TRUE(same(got.data(), want.data(), values * sizeof(float)));
    EXPECT_TRUE(same(got4.data(), want.data(), values * sizeof(float)));
    // Rotations: the planes lerped as above, then x * (1 / sqrt(x^2 + y^2 + z^2 + w^2)) per component.
    auto nlerp_want = [&](auto lerp) {
        std::vector<glm::quat> q(joints);
        for (size_t j = 0; j < joints; ++j) {
            const float x = lerp(j), y = lerp(joints + j), z = lerp(2 * joints + j), w = lerp(3 * joints + j);
            const float inv = 1.0f / std::sqrt(x * x + y * y + z * z + w * w);
            q[j].x = x * inv;
            q[j].y = y * inv;
            q[j].z = z * inv;
            q[j].w = w * inv;
        }
        return q;
    };
    std::vector<glm::quat> qwant = nlerp_want([&](size_t o) {
        return base[o] + step[o] * (wa * static_cast<float>(qa[o]) + wb * static_cast<float>(qb[o]));
    });
    std::vector<glm::quat> qgot(joints), qgot4(joints);
    decode_nlerp(qa.data(), qb.data(), joints, base.data(), step.data(), wa, wb, qgot.data(), joints, true);
    decode_nlerp(qa.data(), qb.data(), joints, base.data(), step.data(), wa, wb, qgot4.data(), joints, false);
    EXPECT_TRUE(same(qgot.data(), qwant.data(), joints * sizeof(glm::quat)));
    EXPECT_TRUE(same(qgot4.data(), qwant.data(), joints * sizeof(glm::quat)));
    qwant = nlerp_want([&](size_t o) { return fa[o] * wa + fb[o] * wb; });
    decode_nlerp(fa.data(), fb.data(), joints, wa, wb, qgot.data(), joints, true);
    decode_nlerp(fa.data(), fb.data(), joints, wa, wb, qgot4.data(), joints, false);
    EXPECT_TRUE(same(qgot.data(), qwant.data(), joints * sizeof(glm::quat)));
    EXPECT_TRUE(same(qgot4.data(), qwant.data(), joints * sizeof(glm::quat)));
}

}  // namespace
}  // namespace aloha
