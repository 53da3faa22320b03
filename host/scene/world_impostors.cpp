// The World's impostor atlases: each character type posed along its walk cycle and standing, baked once
// per renderer (systems/frame/impostor_source.hpp, systems/render/impostor_atlas.hpp).
#include "host/scene/character_runtime.hpp"
#include "host/scene/world.hpp"
#include "engine/core/blob_store.hpp"
#include "engine/gpu/context.hpp"
#include "systems/frame/impostor_share.hpp"
#include "systems/frame/impostor_source.hpp"
#include "systems/motion/kinematic_walk.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/pose_pool.hpp"
#include "systems/render/impostor_atlas_cache.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace aloha {
namespace {

constexpr uint32_t kWalkRows = 8;     // walk phases baked (the 9th row stands)
constexpr uint32_t kDirections = 16;  // azimuths around the vertical axis: 22.5 degrees apart

// Model-space joint matrices of `type` at kWalkRows phases of its slowest gait cycle, then standing: its idle's
// first pose, the root at its rest place (PosePool::set_stance, the stance its characters hold; a file's T- or A-posed
// rest is no one's stance), the rest pose when it has no idle; every row stands when the type has no gait cycle.
// `cycle_s` gets the cycle's clip seconds.
std::vector<std::vector<glm::mat4>> impostor_poses(const CharacterType& type, float& cycle_s) {
    const int joints = type.skeleton.joint_count();
    PosePool pool(joints, kWalkRows + 1, &type.skeleton);
    const AnimationClip* walk = type.gait_clips.empty() ? nullptr : type.clips.find(type.gait_clips.front());
    cycle_s = walk && walk->duration() > 0.0f ? walk->duration() : 1.0f;
    // The idle as idlers play it (its looped version, when its seam was closed): the stance they start in.
    const AnimationClip* idle = type.idle_clip >= 0 ? type.clips.find_looped(static_cast<ClipId>(type.idle_clip)) : nullptr;
    std::vector<std::vector<glm::mat4>> rows;
    for (uint32_t r = 0; r <= kWalkRows; ++r) {
        PoseView pose = pool.view(r);
        if (walk && r < kWalkRows) {
            sample_walk_cycle(*walk, cycle_s * static_cast<float>(r) / static_cast<float>(kWalkRows), nullptr, pose);
            local_to_model(type.skeleton.parents().data(), pose.translations.data(), pose.rotations.data(), pose.scales.data(),
                           nullptr, pose.model.data(), static_cast<size_t>(joints));
        } else if (idle) {
            pool.set_stance(r, *idle, type.skeleton);
        }
        rows.emplace_back(pose.model.begin(), pose.model.end());
    }
    return rows;
}

}  // namespace

Status World::build_impostors() {
    if (!renderer_) return {};
    const auto& levels = rules_.table().geom_levels;
    if (std::none_of(levels.begin(), levels.end(), [](const GeomLevelDef& l) { return l.method == GeomMethod::Impostor; })) return {};
    refresh_type_views();
    impostor_built_.resize(types_.size(), 0);
    // The atlases baked so far and what each was baked from: a later type whose input is one of them scaled
    // (a file character's height variants) draws that atlas scaled instead of baking its own.
    struct Owner {
        size_t report;                // its entry in impostor_reports_
        uint32_t atlas;               // renderer id
        float extent;                 // its rows' height (impostor_vertical_range)
        ImpostorBakeInput input;
    };
    std::vector<Owner> owners;
    for (size_t t = 0; t < types_.size(); ++t) {
        if (impostor_built_[t]) continue;
        const auto t0 = std::chrono::steady_clock::now();
        CharacterRuntime& rt = *types_[t];
        const uint8_t level = impostor_source_level(*rt.geometry);
        impostor_built_[t] = 1;
        if (level == GeometryController::kNoLevel) continue;  // no mesh: its impostor level draws nothing
        if (rt.count == 0) continue;  // no character to draw (a varied crowd's base type): nothing to bake
        float cycle_s = 1.0f;
        const std::vector<std::vector<glm::mat4>> poses = impostor_poses(rt.type, cycle_s);
        ImpostorBakeInput in = impostor_bake_input(draw_types_[t], level, poses, rt.type.name);
        in.directions = kDirections;
        in.elevations = options_.impostor_elevations;
        // The atlases nearest this type's size first: a file character's neighbouring heights differ least.
        const glm::vec2 range = impostor_vertical_range(in);
        const float extent = range.y > range.x ? range.y - range.x : 1.0f;
        const bool sharing = options_.impostor_share_px > 0.0f;
        if (sharing)
            std::sort(owners.begin(), owners.end(), [&](const Owner& a, const Owner& b) {
                return std::abs(std::log(a.extent / extent)) < std::abs(std::log(b.extent / extent));
            });
        const auto shared = !sharing ? owners.end() : std::find_if(owners.begin(), owners.end(), [&](const Owner& o) {
            const ImpostorShare share = impostor_share_between(o.input, in, options_.impostor_share_px);
            if (!share.shareable(options_.impostor_share_px, kImpostorShareToleranceSteps)) return false;
            const ImpostorReport& from = impostor_reports_[o.report];
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            impostor_reports_.push_back({rt.type.name, from.width, from.height, ms, 0, false, from.type, share.scale, share.distance_px});
            draws_.set_impostor(static_cast<uint16_t>(t), o.atlas, cycle_s, share.scale);
            return true;
        });
        if (shared != owners.end()) continue;
        // The bake cache holds atlases by a digest of everything the bake reads and of the device.
        const std::vector<uint8_t> key = bake_cache_ ? impostor_atlas_key(renderer_->context().properties(), in) : std::vector<uint8_t>{};
        std::optional<ImpostorAtlas> read;
        if (bake_cache_)
            if (const auto bytes = bake_cache_->get(key)) read = read_impostor_atlas(*bytes);
        if (read) read->image.name = impostor_atlas_image_name(in.name);  // the name is not in the key: types may share
        const bool cached = read.has_value();
        Result<ImpostorAtlas> atlas = cached ? Result<ImpostorAtlas>(std::move(*read)) : bake_impostor_atlas(renderer_->context(), in);
        if (!atlas) return atlas.error();
        if (bake_cache_ && !cached) bake_cache_->put(key, write_impostor_atlas(atlas.value()));
        Result<uint32_t> id = renderer_->register_impostor_atlas(atlas.value().image, atlas.value().layout);
        if (!id) return id.error();
        draws_.set_impostor(static_cast<uint16_t>(t), id.value(), cycle_s);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        impostor_reports_.push_back({rt.type.name, atlas.value().image.width, atlas.value().image.height, ms, atlas.value().texture_bytes, cached, {}, 1.0f, 0.0f});
        owners.push_back({impostor_reports_.size() - 1, id.value(), extent, std::move(in)});
    }
    return {};
}

}  // namespace aloha
