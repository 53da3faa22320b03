// Request checks of a scene against its character types (see scene_checks.hpp).
#include "host/scene/scene_checks.hpp"

#include "engine/anim/humanoid_map.hpp"

#include <map>

namespace aloha {

ResolvedRequest resolve_request(const CharacterType& type, const RequestDesc& rd) {
    ResolvedRequest out;
    const RequestKind kind = rd.request.kind;
    if (kind == RequestKind::PlayClip && (out.clip = find_clip(type, rd.clip)) < 0)
        out.problem = "unknown clip '" + rd.clip + "' for type '" + type.name + "'";
    if ((kind == RequestKind::Reach || kind == RequestKind::LookAt) && (out.effector = find_joint(type.skeleton, type.map, rd.effector)) < 0)
        out.problem = "unknown effector joint '" + rd.effector + "' for type '" + type.name + "'";
    return out;
}

std::string request_problem(const CharacterType& type, const RequestDesc& rd) { return resolve_request(type, rd).problem; }

std::vector<Error> scene_request_problems(const SceneDesc& scene, const std::vector<const CharacterType*>& types) {
    struct Seen {
        std::string first;  // "character 3 request 1"
        size_t others = 0;
    };
    std::map<std::string, Seen> seen;  // by problem, in message order
    std::vector<std::string> order;
    auto add = [&](const std::string& where, const std::string& problem) {
        auto [it, fresh] = seen.try_emplace(problem, Seen{where, 0});
        if (fresh) order.push_back(problem);
        else ++it->second.others;
    };
    const std::vector<CharacterDesc> characters = expand_characters(scene);
    for (size_t i = 0; i < characters.size(); ++i) {
        const CharacterDesc& c = characters[i];
        if (c.type < 0 || static_cast<size_t>(c.type) >= types.size() || types[static_cast<size_t>(c.type)] == nullptr) continue;
        const CharacterType& type = *types[static_cast<size_t>(c.type)];
        for (size_t k = 0; k < c.requests.size(); ++k)
            if (std::string p = request_problem(type, c.requests[k]); !p.empty()) add("character " + std::to_string(i) + " request " + std::to_string(k), p);
        if (c.overlay)
            if (std::string p = request_problem(type, *c.overlay); !p.empty()) add("character " + std::to_string(i) + " overlay", p);
    }
    std::vector<Error> out;
    for (const std::string& problem : order) {
        const Seen& s = seen.at(problem);
        const std::string more = s.others == 0 ? "" : " (and " + std::to_string(s.others) + " more request" + (s.others == 1 ? "" : "s") + " like it)";
        out.push_back(make_error(scene.file, s.first + ": " + problem + more));
    }
    return out;
}

}  // namespace aloha
