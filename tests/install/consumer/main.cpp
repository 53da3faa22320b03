// mini_game: a game with its own entity store drives ALOHA's systems through spans and renders a frame.
// Walked through in docs/INTEGRATION.md. Usage: mini_game OUT.png
#include "components/lod.hpp"
#include "components/motion.hpp"
#include "components/transform.hpp"
#include "engine/anim/skeleton.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "engine/gpu/png.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/geometry/muscle/muscle_loader.hpp"
#include "systems/lod/attributes.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "systems/lod/rule_table.hpp"
#include "systems/motion/controller.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "systems/motion/walk_rig.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <string>
#include <vector>

using namespace aloha;

namespace {

// The game's own entity store: one plain array per component, index = entity.
struct GameEntities {
    std::vector<Transform> transforms;
    std::vector<Velocity> velocities;
    std::vector<Bounds> bounds;
    std::vector<Importance> importance;
    std::vector<LodAttributes> attributes;
    std::vector<LodRequest> requests;
    std::vector<LodState> lod;
    std::vector<GeomLod> geom;
    std::vector<AnimLod> anim;
    std::vector<MotionState> motion;
};

int fail(const Error& e) {
    std::fprintf(stderr, "mini_game: %s\n", e.to_string().c_str());
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: mini_game OUT.png\n");
        return 2;
    }
    const std::string data = MINI_GAME_DATA_DIR;
    // 1. Data: the knowledge base, the project's humanoid (skeleton for a body, generated idle clip),
    // its muscle layout.
    auto rules = load_rules(data + "/rules/default.json");
    if (!rules.ok()) return fail(rules.error());
    auto humanoid = load_humanoid_definition(data + "/characters/humanoid.json");
    if (!humanoid.ok()) return fail(humanoid.error());
    auto skeleton = build_skeleton(humanoid_skeleton(humanoid.value(), HumanoidBody{1.75f, 0.5f}), "humanoid.json");
    if (!skeleton.ok()) return fail(skeleton.error());
    auto rig = resolve_walk_rig(skeleton.value(), "humanoid.json");
    if (!rig.ok()) return fail(rig.error());
    stand_rig_on_rest_ground(rig.value(), skeleton.value());
    const MotionLibrary library = make_motion_library(skeleton.value(), rig.value(), "humanoid");
    ClipLibrary clips;
    auto clip = clips.add(library.idle, skeleton.value());
    if (!clip.ok()) return fail(clip.error());
    auto muscles = load_muscle_set(data + "/characters/humanoid_muscles.json", skeleton.value());
    if (!muscles.ok()) return fail(muscles.error());

    // 2. Our controllers, sized for the game's characters.
    const uint32_t n = 36;
    MotionController motion(skeleton.value(), clips, n);
    CharacterGeometryDesc desc;
    desc.name = "humanoid";
    desc.skeleton = skeleton.value();
    desc.muscles = muscles.value();
    auto geometry = CharacterGeometry::create(std::move(desc));
    if (!geometry.ok()) return fail(geometry.error());
    std::vector<GeomLod> levels;
    for (size_t l = 0; l < rules.value().geom_levels.size(); ++l) levels.push_back(rules.value().geom_lod(static_cast<uint8_t>(l)));
    GeometryController shapes(*geometry.value(), levels, n);

    // 3. The game's entities: a 6x6 block in front of the camera, each playing the idle clip.
    GameEntities g;
    for (uint32_t i = 0; i < n; ++i) {
        Transform t;
        t.position = glm::vec3(float(i % 6) * 1.5f - 3.75f, 0.0f, -float(i / 6) * 2.0f);
        g.transforms.push_back(t);
        g.velocities.emplace_back();
        g.bounds.push_back(Bounds{1.8f, 0.4f});
        g.importance.push_back(Importance{i == 0 ? 1.0f : 0.3f});
        MotionRequest play;
        play.kind = RequestKind::PlayClip;
        play.clip = clip.value();
        play.start_time = 0.2f * float(i);
        motion.push_request(i, play);
    }
    g.attributes.resize(n);
    g.requests.resize(n);
    g.lod.resize(n);
    g.geom.resize(n);
    g.anim.resize(n);
    g.motion.resize(n);

    // 4. Frames: attributes -> rules -> resolver -> motion -> geometry, all on the game's spans.
    const float dt = 1.0f / 60.0f;
    const LodCamera camera = make_lod_camera(glm::vec3(0, 1.7f, 6.0f), glm::vec3(0, 1.0f, -4.0f), glm::radians(50.0f),
                                             glm::vec2(640, 360), 0.1f, 200.0f);
    std::vector<uint32_t> changed(n);
    const PoseSource poses{motion.poses().view(0).model.data(), static_cast<size_t>(skeleton.value().joint_count())};
    for (int frame = 0; frame < 30; ++frame) {
        LodAttributesJob attributes{g.transforms, g.velocities, g.bounds, g.importance, camera, g.attributes};
        attributes.Run();
        RuleEvalJob eval{&rules.value(), g.attributes, g.lod, rules.value().default_tier, g.requests};
        eval.Run();
        LodResolveJob resolve;
        resolve.table = &rules.value();
        resolve.requests = g.requests;
        resolve.states = g.lod;
        resolve.geom = g.geom;
        resolve.anim = g.anim;
        resolve.changed_indices = changed;
        resolve.snap = frame == 0;
        resolve.dt = frame == 0 ? 0.0f : dt;
        const size_t switched = resolve.Run();
        // Level switches go to the geometric controller (it geomorphs from the old surface).
        if (frame == 0) {
            for (uint32_t c = 0; c < n; ++c) shapes.begin_level(c, g.lod[c].geom_level, -1, 0);
        } else {
            for (size_t k = 0; k < switched; ++k) {
                const uint32_t c = changed[k];
                if (shapes.level_of(c) != g.lod[c].geom_level)
                    shapes.begin_level(c, g.lod[c].geom_level, static_cast<int8_t>(g.lod[c].prev_geom_level),
                                      aloha::transition_frames(g.geom[c].geomorph_s, dt));
            }
        }
        MotionUpdateJob animate{&motion, dt, g.anim, g.motion, g.transforms, g.velocities};
        animate.Run();
        for (uint32_t i = 0; i < n; ++i)
            if (g.geom[i].method != GeomMethod::Hidden) shapes.update(g.lod[i].geom_level, std::span<const uint32_t>(&i, 1), poses, dt);
    }

    // 5. Render one frame headless (lavapipe unless a GPU is present) and write it.
    auto ctx = gpu::Context::create({});
    if (!ctx.ok()) return fail(ctx.error());
    auto renderer = CrowdRenderer::create(*ctx.value());
    if (!renderer.ok()) return fail(renderer.error());
    auto target = gpu::OffscreenTarget::create(*ctx.value(), 640, 360);
    if (!target.ok()) return fail(target.error());
    std::vector<DeformableMesh> meshes;
    std::vector<ProxyInstance> proxies;
    std::vector<std::pair<uint32_t, uint32_t>> topologies;  // geometry topology key -> renderer id
    for (uint32_t i = 0; i < n; ++i) {
        const glm::mat4 world = glm::translate(glm::mat4(1.0f), g.transforms[i].position) * glm::mat4_cast(g.transforms[i].rotation);
        for (const glm::mat4& box : shapes.proxy_boxes(i))
            proxies.push_back({world * box * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), glm::vec4(0.6f, 0.65f, 0.75f, 1.0f)});
        const SurfaceView s = shapes.surface(i);
        if (s.positions.empty()) continue;
        uint32_t topology = ~0u;
        for (const auto& [key, id] : topologies)
            if (key == s.topology_key) topology = id;
        if (topology == ~0u) {
            auto id = renderer.value()->register_topology(shapes.level_indices(s.level), static_cast<uint32_t>(s.positions.size()), true);
            if (!id.ok()) return fail(id.error());
            topologies.emplace_back(s.topology_key, id.value());
            topology = id.value();
        }
        meshes.push_back({topology, s.positions, s.normals, world, glm::vec4(0.86f, 0.68f, 0.56f, 1.0f)});
    }
    FrameInput input;
    input.camera = RenderCamera{camera.view, camera.projection};
    input.meshes = meshes;
    input.proxies = proxies;
    if (Status s = renderer.value()->render(input, target.value()); !s.ok()) return fail(s.error());
    if (Status s = renderer.value()->finish(); !s.ok()) return fail(s.error());
    auto image = target.value().read_back(*ctx.value());
    if (!image.ok()) return fail(image.error());
    if (Status s = gpu::write_png(argv[1], image.value().width, image.value().height, image.value().pixels); !s.ok())
        return fail(s.error());
    std::printf("mini_game: %zu meshes, %zu proxy boxes -> %s\n", meshes.size(), proxies.size(), argv[1]);
    return 0;
}
