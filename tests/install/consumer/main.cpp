// mini_game: a game with its own entity store (a plain array per component, index = entity) places a
// scene file's characters, runs ALOHA's systems and frame glue on its spans, renders the last frame.
// Walked through in docs/INTEGRATION.md. Usage: mini_game SCENE.json OUT.png
#include "aloha/engine/gpu/context.hpp"
#include "aloha/engine/gpu/png.hpp"
#include "aloha/host/scene/character_runtime.hpp"
#include "aloha/host/scene/scene_loader.hpp"
#include "aloha/systems/lod/attributes.hpp"
#include "aloha/systems/lod/resolver.hpp"
#include "aloha/systems/lod/rule_eval.hpp"
#include "aloha/systems/lod/tier.hpp"
#include <cstdio>
using namespace aloha;

struct MiniGame {
    SceneDesc scene; RuleTable rules;
    std::vector<std::unique_ptr<CharacterRuntime>> types;  // our controllers, one per character type
    std::vector<Transform> transforms; std::vector<Velocity> velocities; std::vector<Bounds> bounds; std::vector<Importance> importance;
    std::vector<CharacterRef> refs; std::vector<LodAttributes> attributes; std::vector<LodRequest> requests; std::vector<LodState> lod;
    std::vector<GeomLod> geom; std::vector<AnimLod> anim; std::vector<MotionState> motion; std::vector<uint32_t> changed, scratch;
    std::vector<GeometryType> geometry; std::vector<DrawType> draw;
    CharacterGroups groups; LodCamera camera; uint32_t frame = 0;  // groups: by (type, level), what the loops walk

    Status load(const std::string& file) {
        auto s = load_scene(file); if (!s.ok()) return s.error(); scene = s.value();
        auto r = load_rules(scene.rules); if (!r.ok()) return r.error(); rules = r.value();
        const std::vector<CharacterDesc> chars = expand_characters(scene);  // our runtimes, one per type:
        auto made = make_character_runtimes(scene, chars, geom_levels(rules), true); if (!made.ok()) return made.error();
        types = std::move(made.value());
        for (const CharacterDesc& c : chars) {  // the game's entities, in the scene's order
            CharacterRuntime& rt = *types[size_t(c.type)];
            const uint32_t id = rt.spawned++;
            rt.element_of_character[id] = uint32_t(refs.size());
            if (Status st = rt.queue_requests(scene, refs.size(), c, id); !st.ok()) return st;
            transforms.push_back(character_placement(c)), bounds.push_back({rt.type.height, rt.bounds_radius(c)});
            importance.push_back({c.importance}), refs.push_back({uint16_t(c.type), id});
            lod.emplace_back().always_full = c.always_full, motion.emplace_back().pose_slot = id;
        }
        const size_t n = refs.size();
        velocities.resize(n), attributes.resize(n), requests.resize(n), geom.resize(n), anim.resize(n), changed.resize(n);
        for (const auto& rt : types) geometry.push_back(rt->geometry_type()), draw.push_back(rt->draw_type());
        return {};
    }

    // One frame: LOD attributes -> rules -> resolver -> level switches -> grouping -> motion -> geometry.
    void step() {
        const float dt = scene.dt;
        const CameraKey key = sample_camera(scene.camera, float(frame) * dt);
        camera = make_lod_camera(key.position, key.target, glm::radians(scene.camera.fov_y_deg), glm::vec2(scene.width, scene.height),
                                 scene.camera.near_plane, scene.camera.far_plane);
        LodAttributesJob{transforms, velocities, bounds, importance, camera, attributes}.Run();
        RuleEvalJob{&rules, attributes, lod, resolve_tier(rules, -1, nullptr).tier, requests}.Run();
        const size_t n = LodResolveJob{&rules, requests, lod, geom, anim, {}, changed, 0, frame ? dt : 0.0f, frame == 0}.Run();
        apply_level_switches(geometry, refs, lod, geom, std::span(changed).first(n), frame == 0, dt);
        group_by_level(refs, geom, groups);
        for (const auto& rt : types) MotionUpdateJob{rt->motion.get(), dt, anim, motion, transforms, velocities, rt->element_of_character}.Run();
        const GeometryUpdateJob shapes{geometry, &groups, lod, motion, transforms, dt, frame++ == 0, {}, {}, &scratch};
        shapes.RunMuscles(), shapes.RunSkin();
    }
};

#ifndef MINI_GAME_NO_MAIN
int fail(const Error& e) { return std::fprintf(stderr, "mini_game: %s\n", e.to_string().c_str()), 1; }
int main(int argc, char** argv) {
    MiniGame game; set_data_directory(MINI_GAME_DATA_DIR);  // the installed data (relocatable, from alohaConfig)
    if (Status st = argc == 3 ? game.load(argv[1]) : make_error("mini_game", "usage: mini_game SCENE.json OUT.png"); !st.ok()) return fail(st.error());
    while (game.frame < game.scene.frames) game.step();
    auto ctx = gpu::Context::create({}); if (!ctx.ok()) return fail(ctx.error());
    auto renderer = CrowdRenderer::create(*ctx.value()); if (!renderer.ok()) return fail(renderer.error());
    auto target = gpu::OffscreenTarget::create(*ctx.value(), game.scene.width, game.scene.height); if (!target.ok()) return fail(target.error());
    RenderLists lists;  // the draw lists, gathered with their topology cache, in world space (scale honoured)
    Status st = DrawListBuilder().gather(renderer.value().get(), game.draw, game.groups, game.transforms, game.lod, game.anim, {}, lists);
    FrameInput input{{game.camera.view, game.camera.projection}, lists.meshes, lists.proxies, lists.lines};
    set_character_lighting(input);
    if (st.ok() && (st = renderer.value()->render(input, target.value())).ok()) st = renderer.value()->finish();
    auto image = st.ok() ? target.value().read_back(*ctx.value()) : Result<gpu::Rgba8Image>(st.error()); if (!image.ok()) return fail(image.error());
    if (st = gpu::write_png(argv[2], image.value().width, image.value().height, image.value().pixels); !st.ok()) return fail(st.error());
    std::printf("mini_game: %zu characters, %zu meshes, %zu proxy boxes -> %s\n", game.refs.size(), lists.meshes.size(), lists.proxies.size(), argv[2]);
}
#endif
