#include "systems/render/debug_colours.hpp"

#include <cmath>

namespace aloha {
namespace {

constexpr glm::vec4 rgb8(int r, int g, int b) { return {r / 255.0f, g / 255.0f, b / 255.0f, 1.0f}; }

constexpr glm::vec4 kLevels[kLevelPaletteSize] = {
    rgb8(230, 25, 25),  rgb8(245, 130, 20), rgb8(240, 220, 30),  rgb8(60, 190, 75),
    rgb8(40, 200, 220), rgb8(40, 90, 230),  rgb8(150, 60, 210),  rgb8(240, 50, 230),
    rgb8(170, 110, 40), rgb8(128, 128, 128)};

constexpr glm::vec4 kRules[kRulePaletteSize] = {
    rgb8(230, 25, 75),  rgb8(60, 180, 75),  rgb8(255, 225, 25), rgb8(0, 130, 200),
    rgb8(245, 130, 48), rgb8(145, 30, 180), rgb8(70, 240, 240), rgb8(240, 50, 230),
    rgb8(210, 245, 60), rgb8(250, 190, 212), rgb8(0, 128, 128), rgb8(170, 110, 40)};

constexpr glm::vec4 kMotion[3] = {rgb8(50, 100, 240), rgb8(50, 200, 80), rgb8(250, 150, 30)};

constexpr glm::vec4 kWhite = rgb8(255, 255, 255);
constexpr glm::vec4 kMagenta = rgb8(255, 0, 255);

}  // namespace

glm::vec4 colour_for_level(int level) {
    if (level < 0) return kWhite;
    return kLevels[level % kLevelPaletteSize];
}

glm::vec4 colour_for_rule(int rule_id) {
    if (rule_id < 0) return kWhite;
    return kRules[rule_id % kRulePaletteSize];
}

glm::vec4 colour_for_motion_method(int method) {
    if (method < 0 || method > 2) return kMagenta;
    return kMotion[method];
}

glm::u8vec4 to_rgba8(glm::vec4 colour) {
    const glm::vec4 c = glm::clamp(colour, 0.0f, 1.0f) * 255.0f;
    return glm::u8vec4(static_cast<uint8_t>(std::lround(c.r)), static_cast<uint8_t>(std::lround(c.g)),
                       static_cast<uint8_t>(std::lround(c.b)), static_cast<uint8_t>(std::lround(c.a)));
}

}  // namespace aloha
