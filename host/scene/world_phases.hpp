// The World's frame as data: its phases, in run order, as the Scheduler receives them. Structural changes
// (spawns, despawns, regrouping by level) are applied between phases.
#pragma once

#include "engine/scheduler/phase.hpp"

namespace aloha {

/// The World's phases by position (systems name theirs with these).
struct WorldPhase {
    static constexpr Phase Attributes{0};  ///< LOD attributes from camera and transforms
    static constexpr Phase Rules{1};       ///< occlusion estimate, rule evaluation
    static constexpr Phase Resolve{2};     ///< hysteresis, transitions, budgets, level switches
    static constexpr Phase Motion{3};      ///< the motion controller
    static constexpr Phase Tessellate{4};  ///< muscle shapes and meshes
    static constexpr Phase Skin{5};        ///< fat springs and skin
    static constexpr Phase Render{6};      ///< draw lists, upload, GPU
};

/// The names of the World's phases, in run order (index = WorldPhase position).
inline PhaseList world_phases() { return {"Attributes", "Rules", "Resolve", "Motion", "Tessellate", "Skin", "Render"}; }

}  // namespace aloha
