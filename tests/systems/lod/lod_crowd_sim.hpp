// A synthetic crowd for the lod tests: attributes driven by the test, then each frame the pipeline a
// host runs (rules, level caps, resolver) and a cost model standing in for the measured times.
#pragma once

#include "systems/lod/level_caps.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace aloha::lod_test {

/// Deterministic uniform numbers in [0, 1) (an LCG: same seed, same sequence).
struct Lcg {
    uint32_t state = 7u;
    /// The next number in [0, 1).
    float next() {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f;
    }
};

/// Characters and their LOD components, stepped through rules -> caps -> resolver.
struct CrowdSim {
    const RuleTable* table = nullptr;          ///< the rules (outlives the sim)
    std::vector<LodAttributes> attrs;          ///< set by the test before each frame
    std::vector<LodRequest> req;               ///< the rules' requests of the last frame
    std::vector<LodState> states;              ///< levels, demotions, caps
    std::vector<GeomLod> geom;
    std::vector<AnimLod> anim;
    LevelCapScratch caps_scratch;
    bool first = true;                         ///< the next frame snaps (like a host's first frame)
    float dt = kFrameDt;                       ///< seconds per frame
    uint32_t switches[2] = {0, 0};             ///< geometric / animation level switches so far

    /// A sim of `t` with `n` characters of attributes `a` (copied to all).
    CrowdSim(const RuleTable& t, size_t n, const LodAttributes& a = {}) : table(&t) { resize(n, a); }
    /// Grows (or shrinks) the crowd; new characters get attributes `a` and fresh states.
    void resize(size_t n, const LodAttributes& a = {}) {
        attrs.resize(n, a);
        req.resize(n);
        states.resize(n);
        geom.resize(n);
        anim.resize(n);
    }
    /// One frame: rules, caps (when the table has any), resolver.
    void frame() {
        RuleEvalJob rules{table, attrs, states, table->default_tier, req};
        ASSERT_TRUE(rules.Validate());
        rules.Run();
        LevelCapJob caps{table, req, attrs, states, first, first ? 0.0f : dt, table->hysteresis.band, &caps_scratch};
        std::vector<std::string> errors;
        ASSERT_TRUE(caps.Validate(&errors)) << errors.front();
        caps.Run();
        LodResolveJob resolve{table, req, states, geom, anim, {}, {}, 0, first ? 0.0f : dt, first, switches};
        ASSERT_TRUE(resolve.Validate());
        resolve.Run();
        first = false;
    }
    /// Characters whose geometric (or animation) level is `level` or richer.
    [[nodiscard]] size_t at_or_richer(bool geometric, uint8_t level) const {
        size_t n = 0;
        for (const LodState& s : states) n += (geometric ? s.geom_level : s.anim_level) <= level;
        return n;
    }
};

}  // namespace aloha::lod_test
