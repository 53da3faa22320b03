#include "systems/lod/level_caps.hpp"

#include "systems/lod/resolver.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace aloha {

bool LevelCapJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string m) {
        ok = false;
        if (errors) errors->push_back("LevelCapJob: " + std::move(m));
    };
    if (table == nullptr || table->geom_levels.empty() || table->anim_levels.empty()) fail("needs a loaded rule table with levels");
    if (scratch == nullptr) fail("needs a scratch");
    if (attributes.size() != requests.size()) fail("attributes size differs from requests");
    if (states.size() != requests.size()) fail("states size differs from requests");
    if (!(keep_bonus >= 0.0f)) fail("keep_bonus must be >= 0");
    if (!(dt >= 0.0f) || !std::isfinite(dt)) fail("dt must be finite and >= 0");
    return ok;
}

namespace {

// One kind of level (geometric or animation) at a time.
struct Dimension {
    std::vector<uint32_t> caps;   // per level, kNoCap = none
    std::vector<bool> hidden;     // per level: never a placement (geometric Hidden)
    int last_capped = -1;
};

Dimension geometry_of(const RuleTable& t) {
    Dimension d;
    for (size_t l = 0; l < t.geom_levels.size(); ++l) {
        d.caps.push_back(t.geom_levels[l].max_characters);
        d.hidden.push_back(t.geom_levels[l].method == GeomMethod::Hidden);
        if (d.caps.back() != kNoCap) d.last_capped = static_cast<int>(l);
    }
    return d;
}

Dimension animation_of(const RuleTable& t) {
    Dimension d;
    for (size_t l = 0; l < t.anim_levels.size(); ++l) {
        d.caps.push_back(t.anim_levels[l].max_characters);
        d.hidden.push_back(false);
        if (d.caps.back() != kNoCap) d.last_capped = static_cast<int>(l);
    }
    return d;
}

}  // namespace

size_t LevelCapJob::Run() const {
    const RuleTable& t = *table;
    for (LodState& s : states) s.cap_geom_level = s.cap_anim_level = 0;
    if (!t.has_caps()) return 0;
    LevelCapScratch& sc = *scratch;
    size_t held = 0;
    for (const bool geometric : {true, false}) {
        const Dimension d = geometric ? geometry_of(t) : animation_of(t);
        if (d.last_capped < 0) continue;
        // Rank every character whose starting point is a capped level or richer (in blocks when a runner is
        // given; the sort below orders them wholly, so the blocks' order does not matter).
        auto rank = [&](size_t begin, size_t end, std::vector<std::pair<float, uint32_t>>& out) {
            for (size_t i = begin; i < end; ++i) {
                const LodTargets start = uncapped_outcome(t, requests[i], states[i], snap, dt);
                const int level = geometric ? start.geom : start.anim;
                if (level > d.last_capped || d.hidden[static_cast<size_t>(level)]) continue;
                float score = t.significance.evaluate(attributes[i]);
                const int current = geometric ? states[i].geom_level : states[i].anim_level;
                if (current <= level) score += std::fabs(score) * keep_bonus;  // incumbent
                if (states[i].always_full) score = FLT_MAX;
                out.emplace_back(-score, static_cast<uint32_t>(i));
            }
        };
        sc.ranked.clear();
        constexpr size_t kGrain = 4096;
        if (run_chunks && states.size() > kGrain) {
            const size_t blocks = (states.size() + kGrain - 1) / kGrain;
            if (sc.blocks.size() < blocks) sc.blocks.resize(blocks);
            run_chunks(states.size(), kGrain, [&](size_t b, size_t e) {
                sc.blocks[b / kGrain].clear();
                rank(b, e, sc.blocks[b / kGrain]);
            });
            for (size_t k = 0; k < blocks; ++k) sc.ranked.insert(sc.ranked.end(), sc.blocks[k].begin(), sc.blocks[k].end());
        } else {
            rank(0, states.size(), sc.ranked);
        }
        std::sort(sc.ranked.begin(), sc.ranked.end());
        // used[L] = characters placed at level L or richer, for every capped L.
        sc.used.assign(d.caps.size(), 0);
        const int levels = static_cast<int>(d.caps.size());
        for (const auto& [neg_score, i] : sc.ranked) {
            const LodTargets start = uncapped_outcome(t, requests[i], states[i], snap, dt);
            const int want = geometric ? start.geom : start.anim;
            int level = want;
            for (; level <= d.last_capped; ++level) {
                if (d.hidden[static_cast<size_t>(level)]) continue;
                bool room = true;
                for (int c = level; c <= d.last_capped && room; ++c)
                    room = d.caps[static_cast<size_t>(c)] == kNoCap || sc.used[static_cast<size_t>(c)] < d.caps[static_cast<size_t>(c)];
                if (room) break;
            }
            while (level < levels - 1 && d.hidden[static_cast<size_t>(level)]) ++level;  // never place on Hidden
            for (int c = level; c < levels; ++c) ++sc.used[static_cast<size_t>(c)];
            held += level > want ? 1u : 0u;
            (geometric ? states[i].cap_geom_level : states[i].cap_anim_level) = static_cast<uint8_t>(level);
        }
    }
    return held;
}

}  // namespace aloha
