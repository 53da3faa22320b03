// Level caps: never exceeded on any frame (also while characters move through thresholds under time
// hysteresis), filled in significance order, always_full characters placed first, hidden requests
// never raised, and caps that would leave characters nowhere to go refused by the loader; ranking in blocks
// changes nothing.
#include "systems/lod/level_caps.hpp"
#include "tests/systems/lod/lod_crowd_sim.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::CrowdSim;
using lod_test::Lcg;
using lod_test::must_parse;
using lod_test::small_rules;

constexpr uint32_t kRichCap = 5;     // at most 5 characters at "rich"
constexpr uint32_t kMidCap = 12;     // at most 12 at "mid" or richer
constexpr uint32_t kFullCap = 3;     // at most 3 at animation level "full"

nlohmann::json capped_rules() {
    nlohmann::json j = small_rules();
    j["geometric_levels"][0]["max_characters"] = kRichCap;
    j["geometric_levels"][1]["max_characters"] = kMidCap;
    j["animation_levels"][0]["max_characters"] = kFullCap;
    return j;
}

// n characters at distances 2..30 m (about a quarter want "rich", a third "mid"), importance 0..1.
CrowdSim random_crowd(const RuleTable& t, size_t n, Lcg& rnd) {
    CrowdSim sim(t, n);
    for (LodAttributes& a : sim.attrs) {
        a = at_distance(2.0f + 28.0f * rnd.next());
        a.importance = rnd.next();
    }
    return sim;
}

TEST(LevelCaps, NeverExceededWhileTheCrowdMoves) {
    const RuleTable t = must_parse(capped_rules());
    ASSERT_TRUE(t.has_caps());
    Lcg rnd;
    CrowdSim sim = random_crowd(t, 200, rnd);
    for (int f = 0; f < 600; ++f) {
        // Everyone drifts 0.5 m per frame in and out of the 10 m / 20 m thresholds; importance wanders.
        for (LodAttributes& a : sim.attrs) {
            a.distance = std::clamp(a.distance + (rnd.next() - 0.5f), 1.0f, 35.0f);
            a.projected_height_px = 1000.0f / a.distance;
            a.importance = std::clamp(a.importance + 0.1f * (rnd.next() - 0.5f), 0.0f, 1.0f);
        }
        sim.frame();
        ASSERT_LE(sim.at_or_richer(true, 0), kRichCap) << "frame " << f;
        ASSERT_LE(sim.at_or_richer(true, 1), kMidCap) << "frame " << f;
        ASSERT_LE(sim.at_or_richer(false, 0), kFullCap) << "frame " << f;
    }
    // The caps were really binding: far more characters asked for the capped levels than they hold.
    size_t want_rich = 0;
    for (const LodRequest& r : sim.req) want_rich += r.geom_level == 0;
    EXPECT_GT(want_rich, size_t{2 * kRichCap});
    EXPECT_GT(sim.switches[0], 0u);
}

// The host ranks candidates in blocks on several threads: blocks run in any order give what one pass gives.
TEST(LevelCaps, RankedInBlocksAsInOnePass) {
    const RuleTable t = must_parse(capped_rules());
    Lcg rnd;
    CrowdSim sim = random_crowd(t, 10000, rnd);  // more than one block of 4096
    for (int f = 0; f < 3; ++f) sim.frame();
    std::vector<LodState> serial = sim.states, blocked = sim.states;
    LevelCapScratch a, b;
    LevelCapJob one{&t, sim.req, sim.attrs, serial, false, sim.dt, t.hysteresis.band, &a};
    LevelCapJob split{&t, sim.req, sim.attrs, blocked, false, sim.dt, t.hysteresis.band, &b};
    size_t chunks = 0;
    split.run_chunks = [&](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
        for (size_t k = (count + grain - 1) / grain; k-- > 0;) fn(k * grain, std::min(count, (k + 1) * grain)), ++chunks;
    };
    EXPECT_EQ(one.Run(), split.Run());
    EXPECT_GT(chunks, 2u);
    for (size_t i = 0; i < serial.size(); ++i) {
        ASSERT_EQ(serial[i].cap_geom_level, blocked[i].cap_geom_level) << i;
        ASSERT_EQ(serial[i].cap_anim_level, blocked[i].cap_anim_level) << i;
    }
}

TEST(LevelCaps, FilledInSignificanceOrder) {
    const RuleTable t = must_parse(capped_rules());
    Lcg rnd;
    CrowdSim sim = random_crowd(t, 120, rnd);
    for (int f = 0; f < 40; ++f) sim.frame();  // static crowd: the first frame places, the rest keep

    // Expected, computed here from the definition: the characters wanting "mid" or richer, most
    // significant first; the first kMidCap of them are at mid or richer; of those, the first kRichCap
    // wanting "rich" are at rich.
    std::vector<uint32_t> order;
    for (uint32_t i = 0; i < sim.req.size(); ++i)
        if (sim.req[i].geom_level <= 1) order.push_back(i);
    ASSERT_GT(order.size(), size_t{kMidCap});
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return t.significance.evaluate(sim.attrs[a]) > t.significance.evaluate(sim.attrs[b]);
    });
    std::vector<uint8_t> expected(sim.req.size(), 2);  // everyone else: proxy (or what the rules say)
    uint32_t rich = 0;
    for (size_t k = 0; k < order.size(); ++k) {
        const uint32_t i = order[k];
        if (k >= kMidCap) continue;
        const bool wants_rich = sim.req[i].geom_level == 0;
        expected[i] = wants_rich && rich < kRichCap ? 0 : 1;
        rich += expected[i] == 0;
    }
    for (uint32_t i = 0; i < sim.req.size(); ++i) {
        if (sim.req[i].geom_level > 1) continue;
        EXPECT_EQ(sim.states[i].geom_level, expected[i]) << "character " << i;
    }
    EXPECT_EQ(sim.at_or_richer(true, 0), kRichCap);  // filled, not just respected
    EXPECT_EQ(sim.at_or_richer(true, 1), kMidCap);
    EXPECT_EQ(sim.at_or_richer(false, 0), kFullCap);
}

TEST(LevelCaps, AlwaysFullCharactersArePlacedFirst) {
    const RuleTable t = must_parse(capped_rules());
    Lcg rnd;
    CrowdSim sim = random_crowd(t, 60, rnd);
    // The least significant of those wanting "rich" is marked always_full.
    uint32_t least = UINT32_MAX;
    for (uint32_t i = 0; i < sim.attrs.size(); ++i) {
        if (sim.attrs[i].distance >= 10.0f) continue;
        if (least == UINT32_MAX || t.significance.evaluate(sim.attrs[i]) < t.significance.evaluate(sim.attrs[least])) least = i;
    }
    ASSERT_NE(least, UINT32_MAX);
    sim.states[least].always_full = 1;
    for (int f = 0; f < 10; ++f) sim.frame();
    EXPECT_EQ(sim.states[least].geom_level, 0);
    EXPECT_EQ(sim.states[least].anim_level, 0);
    EXPECT_LE(sim.at_or_richer(true, 0), kRichCap);
}

TEST(LevelCaps, HiddenRequestsStayHiddenAndUncappedTablesAreUntouched) {
    const RuleTable t = must_parse(capped_rules());
    CrowdSim sim(t, 20, at_distance(3.0f));
    for (int i = 0; i < 10; ++i) sim.attrs[static_cast<size_t>(i)].visible = 0;  // the rules hide these
    for (int f = 0; f < 5; ++f) sim.frame();
    for (int i = 0; i < 10; ++i) EXPECT_EQ(sim.states[static_cast<size_t>(i)].geom_level, 3) << i;
    EXPECT_EQ(sim.at_or_richer(true, 0), kRichCap);

    const RuleTable plain = must_parse(small_rules());
    EXPECT_FALSE(plain.has_caps());
    CrowdSim free(plain, 20, at_distance(3.0f));
    for (int f = 0; f < 5; ++f) free.frame();
    EXPECT_EQ(free.at_or_richer(true, 0), 20u);
    for (const LodState& s : free.states) EXPECT_EQ(s.cap_geom_level + s.cap_anim_level, 0);
}

TEST(LevelCaps, CapsThatLeaveNowhereToGoAreRefused) {
    auto errors_of = [](const nlohmann::json& j) {
        std::vector<Error> errors;
        EXPECT_FALSE(parse_rules(j.dump(2), "caps.json", &errors).ok());
        return join_errors(errors);
    };
    nlohmann::json j = small_rules();
    j["geometric_levels"][2]["max_characters"] = 10;  // proxy: the poorest drawn level
    EXPECT_NE(errors_of(j).find("/geometric_levels/2/max_characters"), std::string::npos);
    j = small_rules();
    j["geometric_levels"][3]["max_characters"] = 10;  // hidden
    EXPECT_NE(errors_of(j).find("a hidden level cannot have a cap"), std::string::npos);
    j = small_rules();
    j["animation_levels"][2]["max_characters"] = 10;  // the poorest animation level
    EXPECT_NE(errors_of(j).find("/animation_levels/2/max_characters"), std::string::npos);
    j = small_rules();
    j["geometric_levels"][0]["max_characters"] = -1;
    EXPECT_NE(errors_of(j).find("out of range"), std::string::npos);
}

TEST(LevelCaps, ValidateListsEveryProblem) {
    LevelCapJob job;
    job.keep_bonus = -1.0f;
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    EXPECT_EQ(errors.size(), 3u);  // no table, no scratch, negative bonus
}

}  // namespace
}  // namespace aloha
