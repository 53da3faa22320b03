// Request checks of a scene against its character types (see scene_checks.hpp).
#include "host/scene/scene_checks.hpp"

#include "engine/anim/humanoid_map.hpp"

#include <map>

namespace aloha {

namespace {

// "its clips: 'a', 'b', ..." for an unknown clip's message: the first 16 of the type's clips, then how many more.
std::string clip_list(const CharacterType& type) {
    constexpr size_t kShown = 16;
    std::string names;
    for (size_t id = 0; id < type.clips.size() && id < kShown; ++id)
        names += (names.empty() ? "'" : ", '") + type.clips.find(static_cast<ClipId>(id))->name() + "'";
    if (type.clips.size() > kShown) names += " and " + std::to_string(type.clips.size() - kShown) + " more";
    return names.empty() ? "it has no clips" : "its clips: " + names;
}

}  // namespace

ResolvedRequest resolve_request(const CharacterType& type, const RequestDesc& rd) {
    ResolvedRequest out;
    const RequestKind kind = rd.request.kind;
    if (kind == RequestKind::PlayClip && (out.clip = find_clip(type, rd.clip)) < 0)
        out.problem = "unknown clip '" + rd.clip + "' for type '" + type.name + "' (" +
                      (type.clips.find(type.name + "." + rd.clip) >= 0 ? "clips are named after their type: did you mean '" + type.name + "." + rd.clip + "'?"
                                                                        : clip_list(type)) +
                      ")";
    if ((kind == RequestKind::Reach || kind == RequestKind::LookAt) && (out.effector = find_joint(type.skeleton, type.map, rd.effector)) < 0)
        out.problem = "unknown effector joint '" + rd.effector + "' for type '" + type.name + "'";
    return out;
}

std::string request_problem(const CharacterType& type, const RequestDesc& rd) { return resolve_request(type, rd).problem; }

std::string request_place(const SceneDesc& scene, size_t index, const RequestDesc& rd, size_t k, bool overlay) {
    if (index < scene.characters.size())
        return "/characters/" + std::to_string(index) + (overlay ? "/overlay" : "/requests/" + std::to_string(k));
    size_t member = index - scene.characters.size();
    for (size_t ci = 0; ci < scene.crowds.size(); ++ci) {
        if (member < scene.crowds[ci].count) {
            const RequestKind kind = rd.request.kind;
            return "/crowds/" + std::to_string(ci) + (kind == RequestKind::PlayClip ? "/clip" : kind == RequestKind::Reach ? "/mix/reach" : "");
        }
        member -= scene.crowds[ci].count;
    }
    return "character " + std::to_string(index);  // not one of the scene's: the host's own
}

std::vector<Error> scene_request_problems(const SceneDesc& scene, const std::vector<const CharacterType*>& types) {
    struct Seen {
        std::string first;  // "/characters/3/requests/1"
        size_t others = 0;
    };
    std::map<std::pair<std::string, std::string>, Seen> seen;  // by problem and group of places, in message order
    std::vector<std::pair<std::string, std::string>> order;
    auto add = [&](const std::string& where, const std::string& problem) {
        // Placed characters sharing a problem make one line (the first named); each crowd key makes its own.
        const std::pair<std::string, std::string> key{problem, where.rfind("/crowds/", 0) == 0 ? where : std::string("/characters")};
        auto [it, fresh] = seen.try_emplace(key, Seen{where, 0});
        if (fresh) order.push_back(key);
        else ++it->second.others;
    };
    const std::vector<CharacterDesc> characters = expand_characters(scene);
    for (size_t i = 0; i < characters.size(); ++i) {
        const CharacterDesc& c = characters[i];
        if (c.type < 0 || static_cast<size_t>(c.type) >= types.size() || types[static_cast<size_t>(c.type)] == nullptr) continue;
        const CharacterType& type = *types[static_cast<size_t>(c.type)];
        for (size_t k = 0; k < c.requests.size(); ++k)
            if (std::string p = request_problem(type, c.requests[k]); !p.empty()) add(request_place(scene, i, c.requests[k], k, false), p);
        if (c.overlay)
            if (std::string p = request_problem(type, *c.overlay); !p.empty()) add(request_place(scene, i, *c.overlay, 0, true), p);
    }
    std::vector<Error> out;
    for (const auto& key : order) {
        const Seen& s = seen.at(key);
        const std::string more = s.others == 0 ? "" : " (and " + std::to_string(s.others) + " more request" + (s.others == 1 ? "" : "s") + " like it)";
        out.push_back(make_error(scene.file, key.first + more, 0, 0, s.first));
    }
    return out;
}

}  // namespace aloha
