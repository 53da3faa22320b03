// Shared helpers for the lod tests: a small valid rule file and parsing that fails the test on error.
#pragma once

#include "systems/lod/rule_table.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

namespace aloha::lod_test {

/// The frame time the lod tests step at (60 Hz) unless a test says otherwise.
inline constexpr float kFrameDt = 1.0f / 60.0f;

/// A small valid rule file (min_seconds 0.08: a switch after 5 frames at 60 Hz): 4 geometric levels (rich, mid, proxy, hidden), 3 animation levels,
/// rules near (distance < 10), mid (distance < 20), off (not visible), far (fallback).
inline nlohmann::json small_rules() {
    return nlohmann::json::parse(R"({
      "tiers": ["low", "high"],
      "default_tier": "high",
      "hysteresis": { "band": 0.1, "min_seconds": 0.08 },
      "geometric_levels": [
        { "name": "rich", "method": "layered", "theta_steps": 16, "phi_steps": 12, "geomorph_s": 0.2 },
        { "name": "mid", "method": "skinned_mesh", "geomorph_s": 0.1 },
        { "name": "proxy", "method": "rigid_proxy" },
        { "name": "hidden", "method": "hidden" }
      ],
      "animation_levels": [
        { "name": "full", "walk": "dynamic", "ik": "dls", "ik_iterations": 10, "crossfade_s": 0.15 },
        { "name": "kin", "walk": "kinematic", "ik": "ccd", "ik_iterations": 3, "update_interval": 2, "crossfade_s": 0.05 },
        { "name": "clip", "walk": "clip", "update_interval": 8 }
      ],
      "rules": [
        { "name": "off", "when": { "visible": false }, "then": { "geometry": "hidden", "animation": "clip" } },
        { "name": "near", "when": { "distance": { "lt": 10 } }, "then": { "geometry": "rich", "animation": "full" } },
        { "name": "mid", "when": { "distance": { "lt": 20 } }, "then": { "geometry": "mid", "animation": "kin" } },
        { "name": "far", "then": { "geometry": "proxy", "animation": "clip" } }
      ]
    })");
}

/// Parses `j` and fails the current test (returning an empty table) when it does not load.
inline RuleTable must_parse(const nlohmann::json& j, const std::string& name = "test.json") {
    std::vector<Error> errors;
    Result<RuleTable> r = parse_rules(j.dump(2), name, &errors);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : join_errors(errors));
    return r.ok() ? std::move(r).value() : RuleTable{};
}

/// Attributes of a visible character at `distance` with everything else neutral.
inline LodAttributes at_distance(float distance) {
    LodAttributes a;
    a.distance = distance;
    a.projected_height_px = 1000.0f / distance;
    a.visible = 1;
    a.importance = 0.5f;
    return a;
}

}  // namespace aloha::lod_test
