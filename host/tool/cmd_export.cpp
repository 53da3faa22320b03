// `aloha export SCENE --joints FILE.csv [--characters LIST] [--frames A:B]` (or `--out FILE.glb`, one
// character's skin: cmd_export_skin.cpp): runs the scene headless
// (CPU systems only) and writes, per frame and selected character, every joint's world position with
// the character's animation level, update interval, method and whether a transition is under way.
#include "host/tool/commands.hpp"
#include "host/tool/session.hpp"
#include "systems/lod/rule_table.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace aloha::tool {

namespace {

// The selected spawn indices, in order, or an error naming the first index past the crowd.
Result<std::vector<uint32_t>> selected_characters(const CliOptions& options, size_t count) {
    std::vector<uint32_t> out;
    if (options.character_ranges.empty()) {
        for (uint32_t c = 0; c < count; ++c) out.push_back(c);
        return out;
    }
    std::vector<bool> taken(count, false);
    for (const auto& [lo, hi] : options.character_ranges) {
        if (hi >= count)
            return make_error("command line", "--characters names character " + std::to_string(hi) + " but the scene has " +
                                                  std::to_string(count) + " (indices 0 to " + std::to_string(count - 1) + ")");
        for (uint32_t c = lo; c <= hi; ++c) taken[c] = true;
    }
    for (uint32_t c = 0; c < count; ++c)
        if (taken[c]) out.push_back(c);
    return out;
}

// `text` as one CSV field (RFC 4180): quoted when it holds a comma, quote or line break.
std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string out = "\"";
    for (const char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return out + "\"";
}

}  // namespace

int run_export(const CliOptions& options) {
    if (!check_can_write(options.out.empty() ? options.joints : options.out, options.force)) return 1;
    auto opened = open_session(options, /*render=*/false);
    if (!opened.ok()) {
        print_error(opened.error().to_string());
        return 1;
    }
    Session& s = *opened.value();
    if (!options.out.empty()) return export_skin(options, s);
    World& world = *s.world;
    auto chosen = selected_characters(options, world.character_count());
    if (!chosen.ok()) {
        print_error(chosen.error().to_string());
        return 2;
    }
    const auto [first, end] = options.frame_range.value_or(std::pair<uint32_t, uint32_t>{0, s.scene.frames});
    // Written beside the target and renamed at the end: a failed run leaves nothing half-written.
    const std::string partial = options.joints + ".partial";
    std::ofstream csv(partial);
    if (!csv) {
        print_error("cannot write " + options.joints);
        return 1;
    }
    const RuleTable& table = world.rules().table();
    csv << "frame,time_s,character,type,id,anim_level,level_index,update_interval,method,in_transition,joint,joint_name,x,y,z\n";
    MotionSample sample;
    char xyz[96];
    for (uint32_t f = 0; f < end; ++f) {
        world.step();
        if (f < first) continue;
        for (const uint32_t c : chosen.value()) {
            world.motion_sample(c, sample);
            const CharacterType& type = world.type(sample.type);
            const std::string level = sample.anim_level < table.anim_levels.size() ? table.anim_levels[sample.anim_level].name
                                                                                   : std::to_string(sample.anim_level);
            const std::string head = std::to_string(f) + "," + std::to_string(world.time()) + "," + std::to_string(c) + "," +
                                     csv_field(type.name) + "," + std::to_string(sample.id) + "," + csv_field(level) + "," +
                                     std::to_string(sample.anim_level) + "," + std::to_string(sample.update_interval) + "," +
                                     sample.method + "," + (sample.in_transition ? "1" : "0") + ",";
            for (size_t j = 0; j < sample.joints.size(); ++j) {
                const glm::vec3& p = sample.joints[j];
                std::snprintf(xyz, sizeof xyz, ",%.6f,%.6f,%.6f\n", static_cast<double>(p.x), static_cast<double>(p.y),
                              static_cast<double>(p.z));
                csv << head << j << "," << csv_field(type.skeleton.names()[j]) << xyz;
            }
        }
    }
    csv.close();
    std::error_code ec;
    if (!csv || (std::filesystem::rename(partial, options.joints, ec), ec)) {
        std::filesystem::remove(partial, ec);
        print_error("cannot write " + options.joints);
        return 1;
    }
    std::cout << "exported " << chosen.value().size() << " characters, frames " << first << " to " << end - 1 << ", to "
              << options.joints << "\n";
    return 0;
}

}  // namespace aloha::tool
