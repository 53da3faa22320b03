#include "host/scene/character_type.hpp"

#include "engine/assets/gltf_loader.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "engine/assets/joint_limits.hpp"
#include "host/scene/character_library.hpp"
#include "host/scene/character_loops.hpp"
#include "host/scene/character_motions.hpp"
#include "host/scene/character_rig.hpp"
#include "systems/geometry/controller/body_texture.hpp"
#include "systems/geometry/controller/gltf_character_mesh.hpp"
#include "systems/geometry/controller/skin_layer.hpp"
#include "systems/geometry/muscle/muscle_fit.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"
#include "systems/motion/library/loop_cut.hpp"
#include "systems/motion/library/motion_library.hpp"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cstdio>
#include <optional>

namespace aloha {

namespace {

// A copy of `clip` whose root stays over the origin horizontally (keeps its height): idlers dance in place.
RawAnimation in_place(const RawAnimation& clip, const std::string& name) {
    RawAnimation out = clip;
    out.name = name;
    if (!out.tracks.empty() && !out.tracks[0].translations.values.empty()) {
        auto& v = out.tracks[0].translations.values;
        for (auto& p : v) p.x = 0.0f, p.z = 0.0f;
    }
    return out;
}

// The file clip a type idles in: one named "idle" (any case) first, then one whose name starts with it, then one
// containing it (Quaternius "Idle", Kenney "idle", Ready Player Me "F_Standing_Idle_001"), the shortest name
// winning a tie; null without.
const LoadedTake* named_idle(std::span<const LoadedTake> clips) {
    const LoadedTake* best = nullptr;
    int best_rank = 3;
    size_t best_length = 0;
    for (const LoadedTake& clip : clips) {
        std::string lower = clip.take.name;
        for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        const size_t at = lower.find("idle");
        if (at == std::string::npos) continue;
        const int rank = lower == "idle" ? 0 : at == 0 ? 1 : 2;
        if (rank < best_rank || (rank == best_rank && lower.size() < best_length)) {
            best = &clip;
            best_rank = rank;
            best_length = lower.size();
        }
    }
    return best;
}

// Height and radius of the rest pose from the joints' model positions.
void measure(CharacterType& type) {
    const auto model = rest_model_matrices(type.skeleton);
    glm::vec3 lo(FLT_MAX), hi(-FLT_MAX);
    for (const auto& m : model) {
        lo = glm::min(lo, glm::vec3(m[3]));
        hi = glm::max(hi, glm::vec3(m[3]));
    }
    type.height = std::max(0.5f, (hi.y - lo.y) * 1.08f);  // joints stop short of the skull and soles
    type.radius = std::max(0.2f, 0.5f * std::max(hi.x - lo.x, hi.z - lo.z));
}

Status add_clip(CharacterType& type, const RawAnimation& raw, const std::string& file) {
    auto id = type.clips.add(raw, type.skeleton);
    if (!id.ok()) {
        Error e = id.error();
        if (e.file.empty()) e.file = file;
        return e;
    }
    return {};
}

// The file's skeleton mapped and normalised into `type`; `change` says how (for its clips and mesh).
Status adopt_rig(const Skeleton& original, const CharacterTypeDesc& desc, RigFormat format, const std::string& file,
                 CharacterType& type, RigNormalisation& change, const DeclaredHumanoid& declared = {}) {
    auto rig = normalise_file_rig(original, desc, format, file, declared);
    if (!rig.ok()) return rig.error();
    type.skeleton = std::move(rig.value().skeleton);
    type.map = std::move(rig.value().map);
    type.frame = std::move(rig.value().frame);
    change = std::move(rig.value().change);
    return {};
}

Status load_from_bvh(const CharacterTypeDesc& desc, CharacterType& type, std::vector<RawAnimation>& walk_takes) {
    Result<NormalisedBvh> take = load_normalised_bvh(desc.bvh, desc);
    if (!take.ok()) return take.error();
    NormalisedBvh& t = take.value();
    type.skeleton = std::move(t.rig.skeleton);
    type.map = std::move(t.rig.map);
    type.frame = std::move(t.rig.frame);
    for (const std::string& note : t.notes) type.notes.push_back(note);
    RawAnimation mocap = std::move(t.clip);
    mocap.name = desc.name + ".mocap";
    if (Status s = add_clip(type, mocap, desc.bvh); !s.ok()) return s;
    if (Status s = add_clip(type, in_place(mocap, desc.name + ".inplace"), desc.bvh); !s.ok()) return s;
    type.mocap_clip = 0;
    type.inplace_clip = 1;
    walk_takes.push_back(std::move(mocap));  // tried as a walk once the walk rig is known
    return {};
}

Status load_from_gltf(const CharacterTypeDesc& desc, CharacterType& type, std::vector<RawAnimation>& walk_takes) {
    auto gltf = load_gltf_character(desc.gltf);
    if (!gltf.ok()) return gltf.error();
    GltfCharacter& g = gltf.value();
    auto original = build_skeleton(g.skeleton, desc.gltf);
    if (!original.ok()) return original.error();
    RigNormalisation change;
    if (Status s = adopt_rig(original.value(), desc, RigFormat::Gltf, desc.gltf, type, change, g.humanoid); !s.ok()) return s;
    type.notes = g.notes;
    for (size_t i = 0; i < g.clips.size(); ++i) {
        RawAnimation clip = g.clips[i];
        normalise_clip(clip, original.value(), change);
        clip.name = g.clip_names[i];
        if (Status s = add_clip(type, clip, desc.gltf); !s.ok()) return s;
        if (i == 0) {
            type.mocap_clip = 0;
            if (Status s2 = add_clip(type, in_place(clip, desc.name + ".inplace"), desc.gltf); !s2.ok()) return s2;
            type.inplace_clip = 1;
        }
        walk_takes.push_back(std::move(clip));  // every animation may be a walk or a run: tried once the walk rig is known
    }
    if (!g.meshes.empty()) {
        type.mesh = character_mesh_from_gltf(g, original.value());
        normalise_mesh(*type.mesh, change);
        type.materials = gltf_surface_materials(g);
        type.textures = std::move(g.textures);
    }
    return {};
}

// The project's humanoid: skeleton built for the type's height and build, its muscle layout scaled
// to that body, its joint limits, and the generated motion library (clips named by clip_prefix).
Status load_from_humanoid(const CharacterTypeDesc& desc, CharacterType& type) {
    auto def = load_humanoid_definition(desc.humanoid);
    if (!def.ok()) return def.error();
    const HumanoidBody body{desc.height, desc.build};
    if (Status s = validate_humanoid_body(body, desc.humanoid, "type '" + desc.name + "'"); !s.ok()) return s;
    auto skeleton = build_skeleton(humanoid_skeleton(def.value(), body), desc.humanoid);
    if (!skeleton.ok()) return skeleton.error();
    type.skeleton = std::move(skeleton.value());
    const std::string limits = desc.limits.empty() ? def.value().limits : desc.limits;
    if (!limits.empty()) {
        auto table = load_joint_limits(limits);
        if (!table.ok()) return table.error();
        if (Status s = apply_joint_limits(type.skeleton, table.value()); !s.ok()) return s.error();
    }
    const std::string muscles = desc.muscles.empty() ? def.value().muscles : desc.muscles;
    if (muscles.empty()) return make_error(desc.humanoid, "the humanoid definition names no muscle layout", 0, 0, "/muscles");
    auto defs = load_muscle_defs(muscles);
    if (!defs.ok()) return defs.error();
    // Girth 0.9-1.1 and fat 0.4-1.6 times the layout's from slim to heavy; lengths follow height.
    scale_muscle_defs(defs.value(), desc.height / def.value().reference_height, 0.9f + 0.2f * desc.build,
                      0.4f + 1.2f * desc.build);
    auto set = resolve_muscles(defs.value(), type.skeleton, muscles);
    if (!set.ok()) return set.error();
    type.muscles = std::move(set.value());
    auto rig = resolve_walk_rig(type.skeleton, desc.humanoid);
    if (!rig.ok()) return rig.error();
    stand_rig_on_rest_ground(rig.value(), type.skeleton);
    type.rig = std::move(rig.value());
    const std::string prefix = desc.clip_prefix.empty() ? desc.name : desc.clip_prefix;
    const MotionLibrary lib = make_motion_library(type.skeleton, *type.rig, prefix);
    for (const RawAnimation& gait : lib.gaits) {
        auto id = type.clips.add(gait, type.skeleton);
        if (!id.ok()) return id.error();
        type.gait_clips.push_back(id.value());
    }
    for (const RawAnimation* clip : {&lib.idle, &lib.turn, &lib.wave}) {
        auto id = type.clips.add(*clip, type.skeleton);
        if (!id.ok()) return id.error();
        if (clip == &lib.idle) type.idle_clip = id.value();
    }
    return {};
}

// A type without an authored mesh shows the skin generated from its muscles, with the generated
// body texture (skin, shirt, trousers, shoes; see body_texture.hpp).
void use_generated_look(CharacterType& type) {
    if (type.mesh) return;
    type.materials = {body_material()};
    type.textures = {make_body_texture()};
}

}  // namespace

int find_clip(const CharacterType& type, const std::string& name) {
    if (name.empty()) return type.idle_clip >= 0 ? type.idle_clip : type.inplace_clip;
    return type.clips.find(name);
}

// The scene's choice of walks (desc.walks): each named take of the file cut to its walk loop; one that is not in the
// file or does not loop as a walk is an error at its place in "walks".
Status add_named_walks(CharacterType& type, const CharacterTypeDesc& desc, std::span<const RawAnimation> takes, const std::string& file) {
    for (size_t i = 0; i < desc.walks.size(); ++i) {
        const std::string at = desc.pointer + "/walks/" + std::to_string(i);
        const auto take = std::find_if(takes.begin(), takes.end(), [&](const RawAnimation& t) { return t.name == desc.walks[i]; });
        if (take == takes.end()) {
            std::string names;
            for (const RawAnimation& t : takes) names += (names.empty() ? "'" : ", '") + t.name + "'";
            return make_error(desc.scene_file, "no animation '" + desc.walks[i] + "' in " + file + " (it has " + (names.empty() ? "none" : names) + ")", 0,
                              0, at);
        }
        if (Status w = add_walk_loop(type, *take, file); !w.ok())
            return make_error(desc.scene_file, "'" + desc.walks[i] + "' cannot be a walk: " + w.error().message, 0, 0, at);
    }
    return {};
}

// The type's idle, once every clip is in: the scene's choice (desc.idle; an error at the type's "idle" when it has
// no such clip), else a glTF's own animation named like "Idle" (named_idle over the first `own` of `takes`, the
// file's animations as it names them), else the idle it has (the generated one, or none). An idle among `takes`
// (animations as loaded) is closed where it repeats (close_clip_seam).
Status choose_idle(CharacterType& type, const CharacterTypeDesc& desc, std::span<const LoadedTake> takes, size_t own = 0) {
    std::string name = desc.idle, how = " (the scene's choice)";
    if (name.empty() && !desc.gltf.empty())
        if (const LoadedTake* idle = named_idle(takes.first(std::min(own, takes.size())))) name = idle->take.name, how = "";
    if (name.empty()) return {};
    const int id = type.clips.find(name);
    if (id < 0 && !desc.idle.empty())
        return make_error(desc.scene_file, "type '" + desc.name + "' has no clip '" + desc.idle + "' to idle in (" + std::to_string(type.clips.size()) +
                                               " clips; `aloha validate` lists them)",
                          0, 0, desc.pointer + "/idle");
    if (id < 0) return {};
    type.idle_clip = id;  // idlers play it, characters stand in its first pose
    const auto take = std::find_if(takes.begin(), takes.end(), [&](const LoadedTake& t) { return t.take.name == name; });
    const std::string seam = take == takes.end() ? "" : close_clip_seam(type, static_cast<ClipId>(id), take->take, take->file);
    type.notes.push_back(std::string(how.empty() ? "idle: the file's clip '" : "idle: '") + name + "'" + how + seam);
    return {};
}

Result<CharacterType> load_character_type(const CharacterTypeDesc& desc) {
    CharacterType type;
    type.name = desc.name;
    if (!desc.humanoid.empty()) {
        if (Status s = load_from_humanoid(desc, type); !s.ok()) return s.error();
        auto map = map_humanoid(type.skeleton);
        if (!map.ok()) return map.error();
        type.map = std::move(map.value());
        type.frame.units = "metres (built-in humanoid)";
        type.frame.height = desc.height;
        std::vector<LoadedTake> takes;
        if (Status s = add_motion_files(type, desc, takes); !s.ok()) return s.error();
        if (Status s = choose_idle(type, desc, takes); !s.ok()) return s.error();
        close_clip_seams(type, takes);
        measure(type);
        use_generated_look(type);
        return type;
    }
    std::vector<RawAnimation> walk_takes;
    Status loaded = desc.bvh.empty() ? load_from_gltf(desc, type, walk_takes) : load_from_bvh(desc, type, walk_takes);
    if (!loaded.ok()) return loaded.error();
    const std::string& file = desc.bvh.empty() ? desc.gltf : desc.bvh;
    for (const std::string& note : type.frame.notes) type.notes.push_back(note);
    if (type.map.humanoid) {
        if (Status s = add_canonical_layers(type, desc, file); !s.ok()) return s.error();
    } else {
        if (!desc.limits.empty()) {
            auto limits = load_joint_limits(desc.limits);
            if (!limits.ok()) return limits.error();
            if (Status s = apply_joint_limits(type.skeleton, limits.value()); !s.ok()) return s.error();
        }
        std::string missing;
        for (const std::string& m : type.map.missing) missing += (missing.empty() ? "" : ", ") + m;
        type.notes.push_back("not a humanoid (no " + missing + "): no canonical muscles, limits or reach; add a 'humanoid_map' if it is one");
        if (!desc.muscles.empty()) {
            auto muscles = load_muscle_set(desc.muscles, type.skeleton);
            if (!muscles.ok()) return muscles.error();
            type.muscles = std::move(muscles.value());
        }
    }
    auto rig = resolve_walk_rig(type.skeleton, type.map, file);
    if (rig.ok()) type.rig = std::move(rig.value());
    else type.notes.push_back("no kinematic walk: " + rig.error().to_string());
    if (desc.walks.empty()) {
        add_walk_loops(type, walk_takes, file);  // those that loop as walks (an in-place cycle given root motion by its feet)
    } else if (Status s = add_named_walks(type, desc, walk_takes, file); !s.ok()) {
        return s.error();
    }
    if (type.muscles.size() == 0 && type.mesh && type.map.humanoid) {
        std::vector<glm::mat4> bind_model;
        for (const auto& ibm : type.mesh->inverse_bind) bind_model.push_back(glm::inverse(ibm));
        const std::vector<glm::ivec4> joints = widen_joints(type.mesh->joints);
        MuscleFitOptions options;
        options.fat_thickness *= body_length_scale(type.frame.height);  // a person's fat from 0.5 to 2.5 m, scaled beyond
        options.source_name = desc.gltf;
        auto muscles = fit_muscles_per_bone(type.skeleton, bind_model, type.mesh->positions, joints, type.mesh->weights, options);
        if (!muscles.ok()) return muscles.error();
        type.muscles = std::move(muscles.value());
    } else if (type.muscles.size() == 0) {
        type.notes.push_back(std::string("layered levels refused: muscles are laid out for humanoids and this type is none; ") +
                             (type.mesh ? "drawn with its skinned mesh at those levels" : "drawn as rigid proxies (it has no mesh)"));
    }
    // The file's animations (moved: walking is done with them), the in-place copy of its first, the motion files' clips.
    std::vector<LoadedTake> takes;
    const size_t own = walk_takes.size();
    std::optional<RawAnimation> inplace;
    if (type.inplace_clip >= 0 && !walk_takes.empty()) inplace = in_place(walk_takes.front(), desc.name + ".inplace");
    for (RawAnimation& take : walk_takes) takes.push_back({std::move(take), file});
    if (inplace) takes.push_back({std::move(*inplace), file});
    if (Status s = add_motion_files(type, desc, takes); !s.ok()) return s.error();
    if (Status s = add_generated_motion(type, desc); !s.ok()) return s.error();
    if (Status s = choose_idle(type, desc, takes, own); !s.ok()) return s.error();
    close_clip_seams(type, takes);
    measure(type);
    use_generated_look(type);
    return type;
}

}  // namespace aloha
