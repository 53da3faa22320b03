// A host's phase list for the scheduler tests: seven phases named like the World's, declared here as any
// host would declare its own (the scheduler has no phase names of its own).
#pragma once

#include "engine/scheduler/phase.hpp"

#include <array>

namespace aloha::test {

/// The test host's phases by position.
struct TestPhase {
    static constexpr Phase Attributes{0}, Rules{1}, Resolve{2}, Motion{3}, Tessellate{4}, Skin{5}, Render{6};
};

/// Their names, in run order.
inline PhaseList test_phases() { return {"Attributes", "Rules", "Resolve", "Motion", "Tessellate", "Skin", "Render"}; }

/// Every test phase, in run order.
inline constexpr std::array<Phase, 7> kTestPhases{TestPhase::Attributes, TestPhase::Rules, TestPhase::Resolve, TestPhase::Motion,
                                                  TestPhase::Tessellate, TestPhase::Skin,  TestPhase::Render};

}  // namespace aloha::test
