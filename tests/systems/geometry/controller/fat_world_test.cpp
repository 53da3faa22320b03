// Fat springs that feel the character's world motion (fat_spring_frame.hpp), through the frame glue
// the World and any host call (GeometryUpdateJob with the characters' placements): a sudden stop from a
// run overshoots and settles, any frame rate from 15 to 240 Hz stays finite and within the strain
// limit, a 180 degree snap or a teleport does not fling the skin, and the muscle layout's per-region
// tuning takes effect.
//
// The skin's deviation d = skin - rest end is measured on the fat layer (fat_spring_ends) against
// reference_surface (the same pose with the springs at rest), both before the skin's strain limit
// (strain_limit.hpp), which shapes what is shown on top of the springs. The pose is held fixed, so every deviation comes from the root's motion.
// Bounds (fat_spring.hpp): the strain limit keeps |d| <= D = max_strain * h, with the spring's rest
// length h <= H = sum_k w_k |o_k| (its binding's blended offsets; frames orthonormal), and the rate
// limit keeps the relative speed <= w_n D. Once the root stands still the rest ends are fixed and each
// spring is a free damped oscillator: along its normal (w_n, zeta < 1) |d_n(t)| <= K D e^(-zeta w_n t)
// with K = sqrt(2 / (1 - zeta)) from the worst start (|d0| <= D, |u0| <= w_n D), and a clamp can
// restart that envelope only while it exceeds D (t < ln K / (zeta w_n)), which at most squares K; the
// critically damped lateral part (w_l) obeys |d_l(t)| <= (|d0| + (|u0| + w_l |d0|) t) e^(-w_l t)
// <= D (1 + (w_n + w_l) t) e^(-w_l t), restarted the same way (factor e^(w_l t_l) with t_l the time that
// envelope falls below D). settle_bound() is the sum of both, as a fraction of D.
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include "systems/frame/geometry_frame.hpp"
#include "systems/frame/level_groups.hpp"
#include "systems/geometry/controller/fat_regions.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"
#include "systems/geometry/spring_skin/fat_spring_frame.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace aloha {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

std::vector<float> strain_limits(const CharacterGeometry& g, const FatSpringParams& base);

// One character through GeometryUpdateJob (the spring_skin system's glue) at one Layered level.
struct Walker {
    GeometryController ctl;
    std::vector<GeometryType> types;
    std::vector<CharacterRef> refs{CharacterRef{0, 0}};
    std::vector<GeomLod> geom;
    std::vector<LodState> states{LodState{}};
    std::vector<MotionState> motion{MotionState{}};
    std::vector<Transform> placements{Transform{}};
    std::vector<glm::mat4> pose;
    std::vector<uint32_t> scratch;
    CharacterGroups groups;
    std::vector<float> limit;  ///< per skin vertex: its strain limit (strain_limits)
    bool first = true;

    Walker(const CharacterGeometry& g, const GeomLod& level, std::vector<glm::mat4> p)
        : ctl(g, std::span(&level, 1), 1), geom{level}, pose(std::move(p)) {
        types.push_back({&ctl, PoseSource{pose.data(), pose.size()}});
        group_by_level(refs, geom, groups);
        limit = strain_limits(g, ctl.spring_params());
    }
    /// At the Layered (8, 6) level, held in the walk's first pose.
    explicit Walker(const CharacterGeometry& g)
        : Walker(g, test::grid_level(GeomMethod::Layered, 8, 6), test::clip_pose(g.skeleton(), test::humanoid().clip, 0)) {}
    // One frame of `dt` s with the root at `placement`.
    void step(const Transform& placement, float dt) {
        placements[0] = placement;
        if (first) apply_level_switches(types, refs, states, geom, {}, true, dt);
        const GeometryUpdateJob job{types, &groups, states, motion, placements, dt, first, {}, {}, &scratch};
        EXPECT_TRUE(job.Validate());
        job.RunMuscles();
        job.RunSkin();
        first = false;
    }
    // Per vertex: |skin - rest end| (model space).
    std::vector<float> deviation() const {
        std::vector<glm::vec3> rest;
        ctl.reference_surface(types[0].poses, 0, 0, rest, /*strain_limited=*/false);
        const std::span<const glm::vec3> skin = ctl.fat_spring_ends(0);
        std::vector<float> d(skin.size());
        for (size_t i = 0; i < skin.size(); ++i) d[i] = test::finite(skin[i]) ? glm::length(skin[i] - rest[i]) : INFINITY;
        return d;
    }
    // The largest signed deviation along model +Z (the direction of travel in these runs).
    float forward_overshoot() const {
        std::vector<glm::vec3> rest;
        ctl.reference_surface(types[0].poses, 0, 0, rest, /*strain_limited=*/false);
        const std::span<const glm::vec3> skin = ctl.fat_spring_ends(0);
        float most = -INFINITY;
        for (size_t i = 0; i < skin.size(); ++i) most = std::max(most, skin[i].z - rest[i].z);
        return most;
    }
};

// Per skin vertex of the (8, 6) skin: H = sum_k w_k |o_k| >= its spring's rest length.
std::vector<float> rest_length_bounds(const CharacterGeometry& g) {
    std::vector<float> out;
    for (const BlendBinding& b : g.skin_layer(8, 6).bindings) {
        float h = 0.0f;
        for (int k = 0; k < kBlendInfluences; ++k) h += b.weight[k] * glm::length(b.offset[k]);
        out.push_back(h);
    }
    return out;
}

// Per skin vertex: the tuning its springs use (the controller's, or its fat region's).
std::vector<FatSpringParams> vertex_tunings(const CharacterGeometry& g, const FatSpringParams& base) {
    std::array<FatSpringParams, kMaxSpringTunings> tunings;
    region_spring_params(base, g.muscles().fat_regions, tunings);
    const std::vector<uint8_t> region = vertex_fat_regions(g.skin_layer(8, 6).bindings, g.muscles());
    std::vector<FatSpringParams> out;
    for (size_t i = 0; i < g.skin_layer(8, 6).bindings.size(); ++i) out.push_back(tunings[region.empty() ? 0 : region[i]]);
    return out;
}

// Per skin vertex: the strain limit max_strain * H of its tuning (with float slack).
std::vector<float> strain_limits(const CharacterGeometry& g, const FatSpringParams& base) {
    const std::vector<float> H = rest_length_bounds(g);
    const std::vector<FatSpringParams> tuning = vertex_tunings(g, base);
    std::vector<float> out;
    for (size_t i = 0; i < H.size(); ++i) out.push_back(tuning[i].max_strain * H[i] * (1.0f + 1e-4f) + 1e-6f);
    return out;
}

// The settle envelope of the file comment at `t` s after the stop, as a fraction of D.
double settle_bound(const FatSpringParams& p, double t) {
    const double wn = kTwoPi * p.normal_hz, wl = kTwoPi * p.lateral_hz, z = p.normal_damping;
    const double k = std::sqrt(2.0 / (1.0 - std::min(z, 0.99)));
    double tl = 0.0;  // when the lateral envelope falls below D (it starts at D and may rise first)
    for (double s = 0.0; s < 2.0; s += 1e-4)
        if ((1.0 + (wn + wl) * s) * std::exp(-wl * s) < 1.0 && s > 0.0) {
            tl = s;
            break;
        }
    const double lateral = (1.0 + (wn + wl) * t) * std::exp(-wl * t) * std::exp(wl * tl);
    return k * k * std::exp(-z * wn * t) + lateral;
}

Transform at(glm::vec3 position, float heading_rad = 0.0f) {
    Transform t;
    t.position = position;
    t.rotation = glm::angleAxis(heading_rad, glm::vec3(0.0f, 1.0f, 0.0f));
    return t;
}

struct StopRun {
    float peak = 0.0f;              ///< largest deviation after the stop (m)
    float forward = -INFINITY;      ///< largest overshoot along the travel after the stop (m)
    float before_stop = 0.0f;       ///< largest deviation in the last frame of the steady run (m)
    std::vector<float> settled;     ///< per vertex deviation 0.5 s after the stop
    bool finite = true, within_strain = true;
};

// Runs at 2.5 m/s along +Z for 1 s at `hz`, then stops dead and stands for 0.5 s.
StopRun stop_from_run(const CharacterGeometry& g, float hz) {
    Walker w(g);
    const float dt = 1.0f / hz;
    StopRun out;
    auto check = [&](const std::vector<float>& d) {
        for (size_t i = 0; i < d.size(); ++i) {
            out.finite = out.finite && std::isfinite(d[i]);
            out.within_strain = out.within_strain && d[i] <= w.limit[i];
        }
    };
    const int run_frames = static_cast<int>(std::lround(hz)), stand_frames = static_cast<int>(std::lround(0.5f * hz));
    glm::vec3 position(0.0f);
    for (int f = 0; f < run_frames; ++f) {
        position.z += 2.5f * dt;
        w.step(at(position), dt);
        check(w.deviation());
    }
    const std::vector<float> last = w.deviation();
    out.before_stop = *std::max_element(last.begin(), last.end());
    for (int f = 0; f < stand_frames; ++f) {
        w.step(at(position), dt);
        const std::vector<float> d = w.deviation();
        check(d);
        out.peak = std::max(out.peak, *std::max_element(d.begin(), d.end()));
        out.forward = std::max(out.forward, w.forward_overshoot());
        if (f == stand_frames - 1) out.settled = d;
    }
    return out;
}

TEST(FatWorld, SuddenStopOvershootsThenSettlesWithinHalfASecond) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    const CharacterGeometry& g = *h.geometry;
    const StopRun r = stop_from_run(g, 60.0f);
    ASSERT_TRUE(r.finite);
    EXPECT_TRUE(r.within_strain);
    // A steady run is an inertial frame: after the start has settled (1 s) the skin is at rest.
    EXPECT_LT(r.before_stop, 1e-5f);
    // The stop: the skin carries on forward past its rest ends (a measurable overshoot, > 1 mm).
    EXPECT_GT(r.forward, 1e-3f);
    EXPECT_GT(r.peak, 1e-3f);
    // 0.5 s later every vertex is within the free-oscillator envelope of its tuning (file comment), and
    // that envelope is below 5% of the strain limit for every tuning the layout uses: it has settled.
    const std::vector<float> H = rest_length_bounds(g);
    const GeometryController probe(g, std::vector<GeomLod>{test::grid_level(GeomMethod::Layered, 8, 6)}, 1);
    const std::vector<FatSpringParams> tuning = vertex_tunings(g, probe.spring_params());
    for (size_t i = 0; i < r.settled.size(); ++i) {
        const double bound = settle_bound(tuning[i], 0.5);
        ASSERT_LT(bound, 0.05) << "vertex " << i << ": its tuning does not settle in 0.5 s";
        EXPECT_LE(r.settled[i], bound * tuning[i].max_strain * H[i] + 1e-5) << "vertex " << i;
    }
}

// Springs that start (a character entering a layered level) while the character already walks or runs
// start moving with it (kSpringsStarted): in a steady run, an inertial frame, their rest ends move at
// one constant world velocity, so from the start on the skin stays at its rest ends up to rounding
// (2.5 m/s over 1 s at 60 Hz: positions of a few metres, each frame's carry rounding by ~1e-7 m).
// Springs started from a standstill would lag by the run's speed, up to their strain limit (centimetres).
TEST(FatWorld, AStartWhileRunningDoesNotJoltTheSkin) {
    const CharacterGeometry& g = *test::humanoid().geometry;
    Walker w(g);
    const float dt = 1.0f / 60.0f;
    glm::vec3 position(0.0f, 0.0f, 5.0f);
    float largest = 0.0f;
    for (int f = 0; f < 60; ++f) {
        position.z += 2.5f * dt;
        w.step(at(position), dt);
        const std::vector<float> d = w.deviation();
        largest = std::max(largest, *std::max_element(d.begin(), d.end()));
    }
    EXPECT_LT(largest, 1e-5f);
}

TEST(FatWorld, FiniteAndWithinTheStrainLimitFrom15To240Hz) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    for (const float hz : {15.0f, 30.0f, 240.0f}) {
        const StopRun r = stop_from_run(*h.geometry, hz);
        std::printf("FatWorld: %3.0f Hz, stop from 2.5 m/s: peak %.2f mm, forward overshoot %.2f mm, 0.5 s later %.4f mm\n",
                    static_cast<double>(hz), 1e3 * static_cast<double>(r.peak), 1e3 * static_cast<double>(r.forward),
                    1e3 * static_cast<double>(*std::max_element(r.settled.begin(), r.settled.end())));
        EXPECT_TRUE(r.finite) << hz << " Hz";
        EXPECT_TRUE(r.within_strain) << hz << " Hz";
        EXPECT_GT(r.forward, 1e-3f) << hz << " Hz: the stop shows at every rate";
        EXPECT_LT(*std::max_element(r.settled.begin(), r.settled.end()), 0.05f * r.peak) << hz << " Hz";
    }
}

TEST(FatWorld, TurningWhileRunningStaysBounded) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    Walker w(*h.geometry);
    const float dt = 1.0f / 30.0f;
    glm::vec3 position(0.0f);
    float heading = 0.0f, peak = 0.0f;
    for (int f = 0; f < 90; ++f) {  // 2.5 m/s, turning at 180 deg/s (below the snap rate)
        heading += std::numbers::pi_v<float> * dt;
        position += 2.5f * dt * glm::vec3(std::sin(heading), 0.0f, std::cos(heading));
        w.step(at(position, heading), dt);
        const std::vector<float> d = w.deviation();
        for (size_t i = 0; i < d.size(); ++i) {
            ASSERT_TRUE(std::isfinite(d[i]));
            EXPECT_LE(d[i], w.limit[i]);
            peak = std::max(peak, d[i]);
        }
    }
    EXPECT_GT(peak, 1e-4f);  // a turn is felt (centripetal 2.5 m/s * pi rad/s ~ 7.9 m/s^2)
}

TEST(FatWorld, LandingThrowsTheSkinDownThenSettles) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    Walker w(*h.geometry);
    const float dt = 1.0f / 60.0f;
    glm::vec3 position(0.0f, 0.45f, 0.0f);
    for (int f = 0; f < 10; ++f) w.step(at(position), dt);
    for (float v = 0.0f; position.y > 0.0f;) {  // falls from 0.45 m (g = 9.81 m/s^2), lands at 3 m/s
        v += 9.81f * dt;
        position.y = std::max(0.0f, position.y - v * dt);
        w.step(at(position), dt);
    }
    float down = 0.0f, last = 0.0f;
    std::vector<glm::vec3> rest;
    for (int f = 0; f < 30; ++f) {  // stands for 0.5 s after the landing
        w.step(at(position), dt);
        w.ctl.reference_surface(w.types[0].poses, 0, 0, rest, /*strain_limited=*/false);
        const std::span<const glm::vec3> skin = w.ctl.fat_spring_ends(0);
        last = 0.0f;
        for (size_t i = 0; i < skin.size(); ++i) {
            const float d = glm::length(skin[i] - rest[i]);
            ASSERT_TRUE(std::isfinite(d));
            EXPECT_LE(d, w.limit[i]);
            down = std::max(down, rest[i].y - skin[i].y);
            last = std::max(last, d);
        }
    }
    EXPECT_GT(down, 1e-3f);        // the landing throws the skin down past its rest ends
    EXPECT_LT(last, 0.05f * down);  // and it has settled half a second later (settle_bound, < 5%)
}

TEST(FatWorld, SnapOrTeleportDoesNotFlingTheSkin) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    const CharacterGeometry& g = *h.geometry;
    for (const float hz : {15.0f, 240.0f}) {
        Walker w(g);
        const float dt = 1.0f / hz;
        for (int f = 0; f < 10; ++f) w.step(at(glm::vec3(0.0f)), dt);
        // A 180 degree snap in one frame, then a 100 m teleport: neither is motion; the skin stays at rest.
        w.step(at(glm::vec3(0.0f), std::numbers::pi_v<float>), dt);
        const std::vector<float> snapped = w.deviation();
        EXPECT_LT(*std::max_element(snapped.begin(), snapped.end()), 1e-5f) << hz << " Hz snap";
        w.step(at(glm::vec3(100.0f, 0.0f, 0.0f), std::numbers::pi_v<float>), dt);
        const std::vector<float> d = w.deviation();
        EXPECT_LT(*std::max_element(d.begin(), d.end()), 1e-5f) << hz << " Hz teleport";
        EXPECT_TRUE(spring_frame_change(at(glm::vec3(0.0f)), at(glm::vec3(0.0f), std::numbers::pi_v<float>), dt).snapped);
        EXPECT_FALSE(spring_frame_change(at(glm::vec3(0.0f)), at(glm::vec3(0.0f, 0.0f, 2.5f * dt)), dt).snapped);
    }
}

// A copy of the humanoid whose every muscle is in one fat region tuned `region`.
std::unique_ptr<CharacterGeometry> with_region(const CharacterGeometry& g, const FatRegion& region) {
    CharacterGeometryDesc desc;
    desc.type = 4;
    desc.name = "humanoid_" + region.name;
    desc.skeleton = g.skeleton();
    desc.muscles = g.muscles();
    desc.muscles.fat_regions = {region};
    std::fill(desc.muscles.fat_region.begin(), desc.muscles.fat_region.end(), uint8_t{1});
    auto made = CharacterGeometry::create(std::move(desc));
    EXPECT_TRUE(made.ok()) << (made.ok() ? "" : made.error().to_string());
    return made.ok() ? std::move(made).value() : nullptr;
}

TEST(FatWorld, ASofterRegionMovesMore) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    FatRegion soft{"soft", 3.0f, 0.3f, 3.0f, std::nullopt}, stiff{"stiff", 20.0f, 0.7f, 14.0f, std::nullopt};
    const auto soft_body = with_region(*h.geometry, soft), stiff_body = with_region(*h.geometry, stiff);
    ASSERT_TRUE(soft_body && stiff_body);
    // The sum over the half second after the stop of the largest deviation: the softer springs swing
    // longer (slower decay e^(-zeta w t): 5.7/s against 88/s), so they move more.
    auto motion_after_stop = [](const CharacterGeometry& g) {
        Walker w(g);
        const float dt = 1.0f / 60.0f;
        glm::vec3 position(0.0f);
        for (int f = 0; f < 60; ++f) w.step(at(position += glm::vec3(0.0f, 0.0f, 2.5f * dt)), dt);
        float sum = 0.0f;
        for (int f = 0; f < 30; ++f) {
            w.step(at(position), dt);
            const std::vector<float> d = w.deviation();
            sum += *std::max_element(d.begin(), d.end());
        }
        return sum;
    };
    EXPECT_GT(motion_after_stop(*soft_body), 2.0f * motion_after_stop(*stiff_body));
}

TEST(FatWorld, TheShippedLayoutTunesBellyThighsAndArms) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    const MuscleSet& m = h.geometry->muscles();
    std::vector<std::string> names;
    for (const FatRegion& r : m.fat_regions) names.push_back(r.name);
    for (const char* region : {"belly", "thigh", "arm"}) EXPECT_NE(std::find(names.begin(), names.end(), region), names.end()) << region;
    // Every region is used by some skin vertex (the one its heaviest muscle belongs to).
    const std::vector<uint8_t> per_vertex = vertex_fat_regions(h.geometry->skin_layer(8, 6).bindings, m);
    ASSERT_FALSE(per_vertex.empty());
    for (size_t k = 1; k <= m.fat_regions.size(); ++k)
        EXPECT_NE(std::find(per_vertex.begin(), per_vertex.end(), static_cast<uint8_t>(k)), per_vertex.end()) << m.fat_regions[k - 1].name;
}

// The layout file's "fat_regions" and "fat_region" keys: read as given, bad values named by file and path.
TEST(FatWorld, LayoutReadsRegionsAndNamesBadValues) {
    const auto parse = [](const std::string& regions, const std::string& region_of_muscle) {
        const std::string text = R"({"version": 1, "fat_regions": )" + regions +
                                 R"(, "muscles": [{"name": "m", "fat_region": )" + region_of_muscle +
                                 R"(, "origin": {"joint": "a"}, "insertion": {"joint": "b"}, "radii": [0.02, 0.02]}]})";
        return parse_muscle_defs(nlohmann::json::parse(text), "layout.json");
    };
    const auto good = parse(R"({"soft": {"normal_hz": 3.5, "normal_damping": 0.25, "description": "belly"}})", R"("soft")");
    ASSERT_TRUE(good.ok()) << good.error().to_string();
    ASSERT_TRUE(good.value()[0].fat_region.has_value());
    EXPECT_EQ(good.value()[0].fat_region->name, "soft");
    EXPECT_FLOAT_EQ(*good.value()[0].fat_region->normal_hz, 3.5f);
    EXPECT_FLOAT_EQ(*good.value()[0].fat_region->normal_damping, 0.25f);
    EXPECT_FALSE(good.value()[0].fat_region->lateral_hz.has_value());  // absent: the controller's
    struct Bad {
        std::string regions, region, expect;
    };
    for (const Bad& b : std::vector<Bad>{
             {R"({"soft": {"normal_hz": -1}})", R"("soft")", "/fat_regions/soft/normal_hz"},
             {R"({"soft": {"normal_damping": "high"}})", R"("soft")", "/fat_regions/soft/normal_damping"},
             {R"({"soft": {"max_strain": 5}})", R"("soft")", "/fat_regions/soft/max_strain"},
             {R"({"soft": {"stiffness": 3}})", R"("soft")", "stiffness"},
             {R"({"soft": {}})", R"("hard")", "unknown fat region 'hard'"},
             {R"([1, 2])", R"("soft")", "fat_regions"},
         }) {
        const auto r = parse(b.regions, b.region);
        ASSERT_FALSE(r.ok()) << b.regions;
        const std::string message = r.error().to_string();
        EXPECT_NE(message.find("layout.json"), std::string::npos) << message;
        EXPECT_NE(message.find(b.expect), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace aloha
