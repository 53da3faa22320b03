// derive_passes: turns read/write declarations into ordered passes of non-conflicting systems.
#include <algorithm>
#include <set>

#include "engine/scheduler/scheduler.hpp"

namespace aloha {
namespace {

// Sorted, de-duplicated copy of `ids`.
std::vector<ComponentTypeId> sorted_set(const std::vector<ComponentTypeId>& ids) {
    std::vector<ComponentTypeId> out = ids;
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// The smallest id in both sorted sets, or nothing.
bool first_common(const std::vector<ComponentTypeId>& a, const std::vector<ComponentTypeId>& b,
                  ComponentTypeId& out) {
    auto ia = a.begin();
    auto ib = b.begin();
    while (ia != a.end() && ib != b.end()) {
        if (*ia < *ib) {
            ++ia;
        } else if (*ib < *ia) {
            ++ib;
        } else {
            out = *ia;
            return true;
        }
    }
    return false;
}

std::string quoted_type(ComponentTypeId id) { return "'" + std::string(type_name(id)) + "'"; }

}  // namespace

std::vector<Pass> derive_passes(std::span<const SystemDesc> systems, const PhaseList& phases, std::vector<std::string>& errors) {
    const size_t n = systems.size();
    if (phases.empty() || phases.size() > kMaxPhases)
        errors.push_back("the host declares " + std::to_string(phases.size()) + " phases; 1 to " + std::to_string(kMaxPhases) + " are needed");
    std::set<std::string> phase_names;
    for (const std::string& p : phases)
        if (p.empty() || !phase_names.insert(p).second) errors.push_back("phase names must be unique and non-empty ('" + p + "')");
    std::set<std::string> seen;
    for (size_t i = 0; i < n; ++i) {
        const SystemDesc& s = systems[i];
        if (s.name.empty()) errors.push_back("system #" + std::to_string(i) + " has an empty name");
        else if (!seen.insert(s.name).second) errors.push_back("two systems are named '" + s.name + "'");
        if (!s.run) errors.push_back("system '" + s.name + "' has no run function");
        if (s.phase.index >= phases.size()) {
            errors.push_back("system '" + s.name + "' has phase " + std::to_string(s.phase.index) + " but the host declares " +
                             std::to_string(phases.size()));
        }
    }
    if (!errors.empty()) return {};

    // Writes imply reads: a read-modify-write system conflicts with other readers.
    std::vector<std::vector<ComponentTypeId>> reads(n);
    std::vector<std::vector<ComponentTypeId>> writes(n);
    for (size_t i = 0; i < n; ++i) {
        writes[i] = sorted_set(systems[i].writes);
        std::vector<ComponentTypeId> all = systems[i].reads;
        all.insert(all.end(), systems[i].writes.begin(), systems[i].writes.end());
        reads[i] = sorted_set(all);
    }

    std::vector<Pass> plan;
    for (size_t pi = 0; pi < phases.size(); ++pi) {
        const Phase phase{static_cast<uint8_t>(pi)};
        const std::string& phase_name = phases[pi];
        std::vector<uint32_t> members;  // add() order
        for (uint32_t i = 0; i < n; ++i) {
            if (systems[i].phase == phase) members.push_back(i);
        }
        if (members.empty()) continue;
        const size_t m = members.size();
        // Edges a -> b when b reads something a writes. Two writers of one type are rejected.
        std::vector<std::vector<uint32_t>> after(m);
        std::vector<uint32_t> indegree(m, 0);
        for (size_t a = 0; a < m; ++a) {
            for (size_t b = 0; b < m; ++b) {
                if (a == b) continue;
                const uint32_t sa = members[a];
                const uint32_t sb = members[b];
                ComponentTypeId type = 0;
                if (a < b && first_common(writes[sa], writes[sb], type)) {
                    errors.push_back("systems '" + systems[sa].name + "' and '" + systems[sb].name +
                                     "' both write " + quoted_type(type) + " in phase " +
                                     phase_name +
                                     "; give the type one writer per phase or move one system to "
                                     "another phase");
                    continue;
                }
                if (first_common(writes[sa], reads[sb], type) && !first_common(writes[sa], writes[sb], type)) {
                    after[a].push_back(static_cast<uint32_t>(b));
                    ++indegree[b];
                }
            }
        }
        // Kahn's algorithm by levels: a system's pass is one past the latest pass of the
        // systems it must follow. Within a pass, add() order (members are sorted).
        std::vector<uint32_t> level(m, 0);
        std::vector<uint32_t> ready;
        for (uint32_t k = 0; k < m; ++k) {
            if (indegree[k] == 0) ready.push_back(k);
        }
        size_t done = 0;
        while (!ready.empty()) {
            const uint32_t k = ready.front();
            ready.erase(ready.begin());
            ++done;
            for (const uint32_t b : after[k]) {
                level[b] = std::max(level[b], level[k] + 1);
                if (--indegree[b] == 0) ready.push_back(b);
            }
        }
        if (done != m) {
            std::string names;
            for (uint32_t k = 0; k < m; ++k) {
                if (indegree[k] > 0) names += (names.empty() ? "'" : ", '") + systems[members[k]].name + "'";
            }
            errors.push_back("systems " + names + " of phase " + phase_name +
                             " read what each other writes (a cycle); split them across phases");
            continue;
        }
        const uint32_t levels = *std::max_element(level.begin(), level.end()) + 1;
        for (uint32_t l = 0; l < levels; ++l) {
            Pass pass;
            pass.phase = phase;
            for (uint32_t k = 0; k < m; ++k) {
                if (level[k] == l) pass.systems.push_back(members[k]);
            }
            plan.push_back(std::move(pass));
        }
    }
    if (!errors.empty()) return {};
    return plan;
}

}  // namespace aloha
