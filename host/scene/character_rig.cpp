#include "host/scene/character_rig.hpp"

#include "engine/anim/humanoid_fit.hpp"
#include "engine/assets/bvh_loader.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "engine/assets/joint_limits.hpp"
#include "systems/geometry/controller/skin_layer.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"
#include "systems/geometry/muscle/muscle_retarget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aloha {

Result<NormalisedRig> normalise_file_rig(const Skeleton& original, const CharacterTypeDesc& desc, RigFormat format,
                                         const std::string& file, const DeclaredHumanoid& declared) {
    NormalisedRig rig;
    auto map = map_humanoid(original, desc.humanoid_map, desc.scene_file, desc.pointer + "/humanoid_map", declared);
    if (!map.ok()) return map.error();
    rig.map = std::move(map.value());
    auto frame = detect_rig_frame(original, rig.map, format, desc.scale, file);
    if (!frame.ok()) return frame.error();
    rig.frame = std::move(frame.value());
    if (desc.standing_height > 0.0f) {
        if (!(rig.frame.height > 0.0f)) {
            // A crowd's height range asked for it: the error is at the range, naming the type as the scene does.
            const std::string type = desc.clip_prefix.empty() ? desc.name : desc.clip_prefix;
            return make_error(desc.scene_file,
                              "type '" + type + "' from " + file + " is no mapped humanoid: it has no standing height to vary (give it a " +
                                  "'humanoid_map', or drop the crowd's height range)",
                              0, 0, desc.variant_of.empty() ? desc.pointer : desc.variant_of);
        }
        const float factor = desc.standing_height / rig.frame.height;  // the whole body, clips and mesh alike
        rig.frame.metres_per_unit *= factor;
        rig.frame.height = desc.standing_height;
        char buf[96];
        std::snprintf(buf, sizeof buf, "scaled x%.3f to stand %.2f m tall (a crowd's height variant)", static_cast<double>(factor),
                      static_cast<double>(desc.standing_height));
        rig.frame.notes.push_back(buf);
    }
    rig.change = normalise_rig(original, rig.frame);
    auto skeleton = build_skeleton(rig.change.skeleton, file);
    if (!skeleton.ok()) return skeleton.error();
    rig.skeleton = std::move(skeleton.value());
    return rig;
}

Result<NormalisedBvh> load_normalised_bvh(const std::string& file, const CharacterTypeDesc& desc) {
    BvhOptions options;
    options.unit_scale = 1.0f;  // file units: the rig's units are detected from its height
    Result<BvhData> bvh = load_bvh(file, options);
    if (!bvh.ok()) return bvh.error();
    Result<Skeleton> original = build_skeleton(bvh.value().skeleton, file);
    if (!original.ok()) return original.error();
    Result<NormalisedRig> rig = normalise_file_rig(original.value(), desc, RigFormat::Bvh, file);
    if (!rig.ok()) return rig.error();
    NormalisedBvh out{std::move(rig).value(), std::move(bvh.value().animation), std::move(bvh.value().notes)};
    normalise_clip(out.clip, original.value(), out.rig.change);
    return out;
}

void normalise_mesh(CharacterMesh& mesh, const RigNormalisation& change) {
    const glm::mat4 g = change.global();
    const glm::mat4 g_inv = glm::inverse(g);
    const glm::mat3 a = glm::mat3_cast(change.axes);
    for (glm::vec3& p : mesh.positions) p = glm::vec3(g * glm::vec4(p, 1.0f));
    for (glm::vec3& n : mesh.normals) n = a * n;
    for (size_t j = 0; j < mesh.inverse_bind.size(); ++j)
        mesh.inverse_bind[j] = glm::inverse(change.correction(static_cast<int>(j))) * mesh.inverse_bind[j] * g_inv;
}

Status add_canonical_layers(CharacterType& type, const CharacterTypeDesc& desc, const std::string& file) {
    auto def = load_humanoid_definition(desc.canonical);
    if (!def.ok()) return def.error();
    // The reference humanoid at the rig's own height (any: a 12 m giant's muscles are a 12 m humanoid's, not a
    // 2.5 m one's stretched along its bones), 1.75 m where the height is unknown.
    const float height = type.frame.height > 0.0f && std::isfinite(type.frame.height) ? type.frame.height : 1.75f;
    auto reference = build_skeleton(humanoid_skeleton(def.value(), HumanoidBody{height, 0.5f}), desc.canonical);
    if (!reference.ok()) return reference.error();
    auto reference_map = map_humanoid(reference.value());
    if (!reference_map.ok()) return reference_map.error();
    const CanonicalFit fit = fit_canonical(type.skeleton, type.map, reference.value(), reference_map.value());

    const std::string limits = desc.limits.empty() ? def.value().limits : desc.limits;
    if (!limits.empty()) {
        auto table = load_joint_limits(limits);
        if (!table.ok()) return table.error();
        std::vector<std::string> skipped;
        if (Status s = apply_mapped_joint_limits(type.skeleton, table.value(), type.map, fit, &skipped); !s.ok()) return s;
        if (!skipped.empty()) {
            std::string list;
            for (const std::string& s : skipped) list += (list.empty() ? "" : ", ") + s;
            type.notes.push_back("joint limits left free where the rest bone is turned more than 30 degrees from the reference humanoid's: " + list);
        }
    }
    if (desc.muscles.empty() && type.mesh) return {};  // muscles are fitted to the mesh instead
    const std::string muscles = desc.muscles.empty() ? def.value().muscles : desc.muscles;
    auto defs = load_muscle_defs(muscles);
    if (!defs.ok()) return defs.error();
    // Lengths and girths with the height; fat as a person's from 0.5 to 2.5 m, with the body beyond (body_length_scale).
    if (desc.muscles.empty()) scale_muscle_defs(defs.value(), height / def.value().reference_height, 1.0f, body_length_scale(height));
    const std::vector<MuscleDef> placed = retarget_muscle_defs(defs.value(), type.skeleton, type.map, fit);
    auto set = resolve_muscles(placed, type.skeleton, muscles);
    if (!set.ok()) return set.error();
    type.muscles = std::move(set.value());
    char buf[160];
    std::snprintf(buf, sizeof buf, "muscles: %d from the canonical layout, placed on the mapped bones (%s)",
                  type.muscles.size(), file.c_str());
    type.notes.push_back(buf);
    return {};
}

}  // namespace aloha
