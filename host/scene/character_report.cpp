#include "host/scene/character_report.hpp"

#include <cmath>
#include <cstdio>

namespace aloha {

std::vector<std::string> character_capabilities(const CharacterType& type) {
    std::vector<std::string> out;
    // The clips by name and length, as scene requests name them ("play", "clip"), and what root motion a played one
    // gives; the first 12.
    std::string names;
    for (size_t i = 0; i < type.clips.size() && i < 12; ++i) {
        const AnimationClip* clip = type.clips.find(static_cast<ClipId>(i));
        char buf[96];
        std::snprintf(buf, sizeof buf, " %.2f s", static_cast<double>(clip->duration()));
        std::string entry = clip->name() + buf;
        const RootMotionTrack& root = clip->root_motion();
        if (root.moves()) {  // played, its travel and turn move the character (systems/motion/root_motion.hpp)
            const long degrees = std::lround(static_cast<double>(root.net_turn()) * 57.29577951308232);
            std::string motion;
            if (root.net_travel() >= 0.005f) std::snprintf(buf, sizeof buf, "%.2f m", static_cast<double>(root.net_travel())), motion = buf;
            if (degrees != 0) std::snprintf(buf, sizeof buf, "%ld deg", degrees), motion += (motion.empty() ? "" : ", ") + std::string(buf);
            entry += " (root motion" + (motion.empty() ? std::string(")") : ": " + motion + ")");
        }
        names += (names.empty() ? "" : ", ") + entry;
    }
    if (type.clips.size() > 12) names += ", and " + std::to_string(type.clips.size() - 12) + " more";
    out.push_back("clip playback: yes (" + std::to_string(type.clips.size()) + " clips" + (names.empty() ? "" : ": " + names) + ")");
    out.push_back(type.rig ? "kinematic and dynamic walk: yes" : "kinematic and dynamic walk: no (no two-legged walk rig)");
    const bool arms = type.map.find("RightWrist") >= 0 && type.map.find("LeftWrist") >= 0;
    out.push_back(arms ? "reach: yes (canonical wrists, hands, ankles, toes)" : "reach: only by file joint name (no canonical wrists)");
    out.push_back(type.map.find("Head") >= 0 ? "look-at: yes (canonical Head)" : "look-at: only by file joint name (no canonical Head)");
    out.push_back("geometric level rigid proxy: yes");
    const bool muscles = type.muscles.size() > 0;
    out.push_back(type.mesh ? "geometric level skinned mesh: yes (the file's mesh)"
                            : muscles ? "geometric level skinned mesh: yes (generated from the muscles)"
                                      : "geometric level skinned mesh: no (no mesh and no muscles)");
    out.push_back(muscles ? "geometric levels layered and subdivided: yes (" + std::to_string(type.muscles.size()) + " muscles)"
                          : std::string("geometric levels layered and subdivided: refused (no muscles; drawn ") +
                                (type.mesh ? "with the skinned mesh)" : "as rigid proxies)"));
    return out;
}

std::vector<std::string> character_report(const CharacterType& type) {
    std::vector<std::string> out;
    const auto canon = canonical_humanoid();
    std::string convention = type.map.convention.empty() ? "no naming convention matched" : "convention " + type.map.convention;
    if (type.map.humanoid) {
        convention += ": humanoid";
    } else {
        std::string missing;
        for (const std::string& m : type.map.missing) missing += (missing.empty() ? "" : ", ") + m;
        convention += ": not a humanoid (missing " + missing + ")";
    }
    out.push_back(convention);
    std::string mapping;
    int mapped = 0;
    for (size_t c = 0; c < canon.size() && c < type.map.joint.size(); ++c) {
        const int j = type.map.joint[c];
        if (j < 0) continue;
        ++mapped;
        mapping += (mapping.empty() ? "" : ", ") + std::string(canon[c].name) + " <- " + type.skeleton.names()[static_cast<size_t>(j)];
        if (c < type.map.from_explicit.size() && type.map.from_explicit[c]) mapping += " (humanoid_map)";
        if (c < type.map.from_declared.size() && type.map.from_declared[c]) mapping += " (file)";
    }
    out.push_back("mapping (canonical <- file, " + std::to_string(mapped) + " of " + std::to_string(canon.size()) +
                  "): " + (mapping.empty() ? "none" : mapping));
    const std::vector<std::string> ignored = unmapped_joints(type.skeleton, type.map);
    std::string list;
    for (const std::string& n : ignored) list += (list.empty() ? "" : ", ") + n;
    out.push_back("joints ignored by the layers (" + std::to_string(ignored.size()) + "): " + (list.empty() ? "none" : list));
    std::string units = "units: " + type.frame.units;
    if (!type.frame.up.empty()) units += "; file axes: up " + type.frame.up + ", forward " + type.frame.forward;
    if (type.frame.height > 0.0f) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "; standing height %.2f m", static_cast<double>(type.frame.height));
        units += buf;
    }
    out.push_back(units);
    for (const std::string& c : character_capabilities(type)) out.push_back(c);
    for (const std::string& n : type.notes) out.push_back("note: " + n);
    return out;
}

}  // namespace aloha
