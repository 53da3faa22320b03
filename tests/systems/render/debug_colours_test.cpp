// Debug palettes: exact 8-bit representability, distinctness within each palette, wrapping.
#include "systems/render/debug_colours.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace aloha {
namespace {

// A palette colour must survive to_rgba8 exactly: c * 255 is an integer (to float rounding, 1e-4).
void expect_exact_8bit(glm::vec4 c) {
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(c[k] * 255.0f, std::round(c[k] * 255.0f), 1e-4f);
}

TEST(DebugColours, PalettesAreDistinctAndExact) {
    std::set<uint32_t> levels, rules, motion;
    auto pack = [](glm::vec4 c) {
        const glm::u8vec4 b = to_rgba8(c);
        return uint32_t(b.r) << 24 | uint32_t(b.g) << 16 | uint32_t(b.b) << 8 | b.a;
    };
    for (int i = 0; i < kLevelPaletteSize; ++i) {
        expect_exact_8bit(colour_for_level(i));
        levels.insert(pack(colour_for_level(i)));
    }
    for (int i = 0; i < kRulePaletteSize; ++i) {
        expect_exact_8bit(colour_for_rule(i));
        rules.insert(pack(colour_for_rule(i)));
    }
    for (int i = 0; i < 3; ++i) motion.insert(pack(colour_for_motion_method(i)));
    EXPECT_EQ(levels.size(), size_t(kLevelPaletteSize));
    EXPECT_EQ(rules.size(), size_t(kRulePaletteSize));
    EXPECT_EQ(motion.size(), 3u);
}

TEST(DebugColours, WrapAndOutOfRange) {
    EXPECT_EQ(colour_for_level(kLevelPaletteSize + 1), colour_for_level(1));
    EXPECT_EQ(colour_for_rule(kRulePaletteSize * 3 + 2), colour_for_rule(2));
    EXPECT_EQ(colour_for_level(-1), glm::vec4(1.0f));
    EXPECT_EQ(to_rgba8(colour_for_motion_method(7)), glm::u8vec4(255, 0, 255, 255));
    EXPECT_EQ(to_rgba8({2.0f, -1.0f, 0.5f, 1.0f}), glm::u8vec4(255, 0, 128, 255));  // clamped, rounded
}

}  // namespace
}  // namespace aloha
