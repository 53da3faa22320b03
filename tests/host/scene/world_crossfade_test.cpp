// A character switching between the impostor level and a drawn level, or between the skinned level and a
// layered one, in a World with a renderer: the switch is cross-faded over the longer of the two levels' geomorph
// frames (LevelFade), the draw lists holding the character twice with complementary shares, and the level being
// left stays posed while it fades. And a character wholly outside the view is left out of the draw lists
// at whatever level it is held.
#include "engine/gpu/context.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "host/scene/character_runtime.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"
#include "systems/lod/resolver.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace aloha {
namespace {

const std::string kData = std::string(ALOHA_SOURCE_DIR) + "/data/";

// Geometric levels of data/rules/default.json (4 and 5 are skinned_fine and skinned_light).
constexpr uint8_t kLayeredHigh = 1, kLayeredLow = 2, kSkinned = 3, kProxy = 6, kImpostor = 7;

struct Fixture {
    std::unique_ptr<gpu::Context> ctx;
    std::unique_ptr<CrowdRenderer> renderer;
    gpu::OffscreenTarget target;
    std::unique_ptr<World> world;
};

// `scene` (the close-up walker, one character on a circle, by default) with the default rules, drawn into a
// 160 x 240 target.
bool make(Fixture& f, Result<SceneDesc> scene = load_scene(kData + "scenes/closeup.json")) {
    EXPECT_TRUE(scene.ok());
    if (!scene.ok()) return false;
    SceneDesc s = scene.value();
    s.width = 160;
    s.height = 240;
    gpu::ContextOptions co;
    co.validation = true;
    co.device = "lavapipe";
    auto ctx = gpu::Context::create(co);
    EXPECT_TRUE(ctx.ok()) << (ctx.ok() ? "" : ctx.error().to_string());
    if (!ctx.ok()) return false;
    f.ctx = std::move(ctx).value();
    auto renderer = CrowdRenderer::create(*f.ctx);
    EXPECT_TRUE(renderer.ok());
    if (!renderer.ok()) return false;
    f.renderer = std::move(renderer).value();
    auto target = gpu::OffscreenTarget::create(*f.ctx, s.width, s.height);
    EXPECT_TRUE(target.ok());
    if (!target.ok()) return false;
    f.target = std::move(target).value();
    auto world = World::create(s, {});
    EXPECT_TRUE(world.ok()) << (world.ok() ? "" : world.error().to_string());
    if (!world.ok()) return false;
    f.world = std::move(world).value();
    EXPECT_TRUE(f.world->attach_renderer(f.renderer.get(), &f.target).ok());
    return true;
}

// Pins character 0 at `level` and steps past the hysteresis hold (0.2 s) so the next pin switches at once.
void settle_at(World& w, uint8_t level) {
    ASSERT_TRUE(w.pin_geom_level(0, level).ok());
    for (int i = 0; i < 20; ++i) w.step();
    ASSERT_TRUE(w.render_status().ok()) << w.render_status().error().to_string();
    ASSERT_EQ(w.render_lists().drawn_twice, 0u);
}

// What one frame of a fade drew of the character: its drawn share on the drawn side (mesh or proxies) and
// the impostor's fade value.
struct Drawn {
    uint32_t drawn_twice = 0;
    size_t meshes = 0, proxies = 0, impostors = 0;
    float mesh_dither = -1.0f, proxy_share = -1.0f, impostor_w = -2.0f;
};

Drawn drawn(const World& w) {
    const RenderLists& l = w.render_lists();
    Drawn d;
    d.drawn_twice = l.drawn_twice;
    d.meshes = l.meshes.size();
    d.proxies = l.proxies.size();
    d.impostors = l.impostors.size();
    if (!l.meshes.empty()) d.mesh_dither = l.meshes[0].dither;
    if (!l.proxy_fades.empty()) d.proxy_share = l.proxy_fades[0].share;
    if (!l.impostors.empty()) d.impostor_w = l.impostors[0].forward_phase.w;
    return d;
}

// Frame k of a fade of n frames out of the impostor: the entered level's share `entered_share` (its mesh's
// dither or its boxes' run share) is k / n and the impostor keeps the complement; frame n has no impostor.
void expect_fade_in_frame(const Drawn& d, uint16_t k, uint16_t n, float entered_share, const std::string& what) {
    SCOPED_TRACE(what + ", frame " + std::to_string(k));
    if (k == n) {
        EXPECT_EQ(d.drawn_twice, 0u);
        EXPECT_EQ(d.impostors, 0u);
        return;
    }
    const float share = float(k) / float(n);
    EXPECT_EQ(d.drawn_twice, 1u);
    EXPECT_EQ(d.impostors, 1u);
    EXPECT_EQ(entered_share, share);
    EXPECT_EQ(d.impostor_w, -share);
}

TEST(WorldCrossFade, SwitchesIntoAndOutOfTheImpostorFadeOverTheGeomorphFrames) {
    Fixture f;
    if (!make(f)) return;
    World& w = *f.world;
    const GeometryController& gc = *w.runtime(0).geometry;
    // The frames of a switch into a level: its geomorph_s over the scene's dt (0.1 s at 1/60 s: 6), frame
    // k = 1..N - 1 drawing both, the entered level with k / N of the pixels.
    const uint16_t n_impostor = transition_frames(gc.level(kImpostor).geomorph_s, 0.0166667f);
    const uint16_t n_skinned = transition_frames(gc.level(kSkinned).geomorph_s, 0.0166667f);
    ASSERT_EQ(n_impostor, 6u);
    ASSERT_EQ(n_skinned, 6u);

    // skinned -> impostor: the skinned mesh, kept posed, fades out.
    settle_at(w, kSkinned);
    ASSERT_TRUE(w.pin_geom_level(0, kImpostor).ok());
    std::vector<glm::vec3> reference, previous;
    for (uint16_t k = 1; k <= n_impostor; ++k) {
        SCOPED_TRACE("into the impostor, frame " + std::to_string(k));
        w.step();
        const Drawn d = drawn(w);
        EXPECT_EQ(d.impostors, 1u);
        if (k == n_impostor) {  // frame N: the impostor alone
            EXPECT_EQ(d.drawn_twice, 0u);
            EXPECT_EQ(d.meshes, 0u);
            EXPECT_EQ(d.impostor_w, 1.0f);
            EXPECT_TRUE(gc.fades().empty());
            continue;
        }
        const float share = float(n_impostor - k) / float(n_impostor);
        EXPECT_EQ(d.drawn_twice, 1u);
        ASSERT_EQ(d.meshes, 1u);
        EXPECT_EQ(d.mesh_dither, share);
        EXPECT_EQ(d.impostor_w, -share);
        // The mesh shown is the skinned level's surface for this frame's pose (the pose is evaluated while
        // fading: PoseUse::EveryFrame), not the last one shown before the switch.
        const SurfaceView kept = gc.fade_surface(0);
        ASSERT_EQ(kept.level, kSkinned);
        gc.reference_surface(w.draw_types()[0].poses, 0, kSkinned, reference);
        ASSERT_EQ(reference.size(), kept.positions.size());
        float worst = 0.0f, moved = 0.0f;
        for (size_t i = 0; i < reference.size(); ++i) {
            worst = std::max(worst, glm::length(reference[i] - kept.positions[i]));
            if (!previous.empty()) moved = std::max(moved, glm::length(previous[i] - kept.positions[i]));
        }
        EXPECT_LT(worst, 1e-5f);  // the same linear-blend skin of the same pose: float rounding only
        if (!previous.empty()) {
            EXPECT_GT(moved, 1e-3f) << "the walker's skin moves between frames";
        }
        previous.assign(kept.positions.begin(), kept.positions.end());
    }

    // impostor -> skinned: the entered mesh fades in over the skinned level's frames.
    for (int i = 0; i < 20; ++i) w.step();
    ASSERT_TRUE(w.pin_geom_level(0, kSkinned).ok());
    for (uint16_t k = 1; k <= n_skinned; ++k) {
        w.step();
        const Drawn d = drawn(w);
        ASSERT_EQ(d.meshes, 1u) << "frame " << k;
        expect_fade_in_frame(d, k, n_skinned, d.mesh_dither, "impostor -> skinned");
        if (k == n_skinned) {
            EXPECT_EQ(d.mesh_dither, 1.0f);
        }
    }

    // layered -> impostor: the layered skin (muscles, fat springs) is kept and drawn while fading, over the
    // longer of the two levels' times (layered_low 0.133 s: 8 frames).
    const uint16_t n_layered = transition_frames(std::max(gc.level(kLayeredLow).geomorph_s, gc.level(kImpostor).geomorph_s), 0.0166667f);
    ASSERT_EQ(n_layered, 8u);
    settle_at(w, kLayeredLow);
    ASSERT_TRUE(w.pin_geom_level(0, kImpostor).ok());
    for (uint16_t k = 1; k < n_layered; ++k) {
        w.step();
        const Drawn d = drawn(w);
        EXPECT_EQ(d.drawn_twice, 1u) << "frame " << k;
        EXPECT_EQ(d.meshes, 1u) << "frame " << k;
        EXPECT_EQ(gc.fade_surface(0).level, kLayeredLow);
    }
    w.step();
    EXPECT_EQ(drawn(w).drawn_twice, 0u);

    // impostor -> proxy: the proxy level's geomorph_s is 0 in the default rules, but a fade takes the longer of
    // the two levels' times: the boxes fade in over the impostor's N frames, k / N of the pixels on frame k, the
    // impostor keeping the complement (it was a one-frame pop).
    ASSERT_EQ(transition_frames(gc.level(kProxy).geomorph_s, 0.0166667f), 0u);
    for (int i = 0; i < 20; ++i) w.step();
    ASSERT_TRUE(w.pin_geom_level(0, kProxy).ok());
    for (uint16_t k = 1; k <= n_impostor; ++k) {
        w.step();
        const Drawn d = drawn(w);
        // The fading boxes are one dithered run (all of them) until frame N, then none.
        const std::vector<ProxyFade>& runs = w.render_lists().proxy_fades;
        EXPECT_EQ(runs.size(), k == n_impostor ? 0u : 1u) << "frame " << k;
        if (!runs.empty()) {
            EXPECT_EQ(runs[0].count, d.proxies);
        }
        EXPECT_GT(d.proxies, 0u) << "frame " << k;
        expect_fade_in_frame(d, k, n_impostor, d.proxy_share, "impostor -> proxy");
    }
    // proxy -> impostor: the boxes fade out as one dithered run.
    for (int i = 0; i < 20; ++i) w.step();
    ASSERT_TRUE(w.pin_geom_level(0, kImpostor).ok());
    for (uint16_t k = 1; k < n_impostor; ++k) {
        w.step();
        const Drawn d = drawn(w);
        const float share = float(n_impostor - k) / float(n_impostor);
        EXPECT_EQ(d.drawn_twice, 1u) << "frame " << k;
        ASSERT_EQ(w.render_lists().proxy_fades.size(), 1u) << "frame " << k;
        EXPECT_EQ(w.render_lists().proxy_fades[0].count, d.proxies);
        EXPECT_EQ(d.proxy_share, share);
        EXPECT_EQ(d.impostor_w, -share);
    }
    w.step();
    EXPECT_EQ(drawn(w).drawn_twice, 0u);
    EXPECT_EQ(drawn(w).proxies, 0u);
    EXPECT_TRUE(w.render_status().ok()) << w.render_status().error().to_string();
    f.world.reset();
    f.renderer.reset();
    EXPECT_EQ(f.ctx->validation_message_count(), 0u);
}

// skinned -> layered_low (crowd_dense's popping switch under near_software), layered_low -> skinned and
// skinned -> layered_high: both meshes drawn on frames 1 .. N - 1, the entered one at k / N and the left one at
// -k / N (the complement), the left mesh the skinned level's skin of each frame's pose; at frame N the entered
// mesh alone and the left level's slot dropped. N: the longer of the two levels' geomorph_s.
TEST(WorldCrossFade, SkinnedAndLayeredSwitchesFadeBetweenTheTwoMeshesAndThenDropTheOldSurface) {
    Fixture f;
    if (!make(f)) return;
    World& w = *f.world;
    const GeometryController& gc = *w.runtime(0).geometry;
    struct Case {
        uint8_t from, to;
    };
    for (const Case sw : {Case{kSkinned, kLayeredLow}, Case{kLayeredLow, kSkinned}, Case{kSkinned, kLayeredHigh}}) {
        SCOPED_TRACE("level " + std::to_string(sw.from) + " -> " + std::to_string(sw.to));
        const uint16_t n = transition_frames(std::max(gc.level(sw.from).geomorph_s, gc.level(sw.to).geomorph_s), 0.0166667f);
        ASSERT_EQ(n, sw.to == kLayeredHigh ? 10u : 8u);  // layered_high 0.167 s, layered_low 0.133 s, skinned 0.1 s
        settle_at(w, sw.from);
        ASSERT_EQ(gc.characters_at(sw.from), 1u);
        ASSERT_TRUE(w.pin_geom_level(0, sw.to).ok());
        std::vector<glm::vec3> reference;
        for (uint16_t k = 1; k <= n; ++k) {
            SCOPED_TRACE("frame " + std::to_string(k));
            w.step();
            ASSERT_TRUE(w.render_status().ok()) << w.render_status().error().to_string();
            const RenderLists& l = w.render_lists();
            EXPECT_TRUE(l.impostors.empty());
            if (k == n) {  // the entered mesh alone; the left level's slot is gone
                EXPECT_EQ(l.drawn_twice, 0u);
                ASSERT_EQ(l.meshes.size(), 1u);
                EXPECT_EQ(l.meshes[0].dither, 1.0f);
                EXPECT_EQ(l.meshes[0].positions.size(), gc.vertices_per_character(sw.to));
                EXPECT_EQ(gc.fade(0), nullptr);
                EXPECT_EQ(gc.characters_at(sw.from), 0u);
                EXPECT_TRUE(gc.fade_surface(0).positions.empty());
                continue;
            }
            const float share = float(k) / float(n);
            EXPECT_EQ(l.drawn_twice, 1u);
            ASSERT_EQ(l.meshes.size(), 2u);
            const DeformableMesh& entered = l.meshes[0].dither > 0.0f ? l.meshes[0] : l.meshes[1];
            const DeformableMesh& left = l.meshes[0].dither > 0.0f ? l.meshes[1] : l.meshes[0];
            EXPECT_EQ(entered.dither, share);
            EXPECT_EQ(left.dither, -share);
            EXPECT_NE(entered.topology, left.topology);
            EXPECT_EQ(entered.positions.size(), gc.vertices_per_character(sw.to));
            EXPECT_EQ(left.positions.size(), gc.vertices_per_character(sw.from));
            EXPECT_EQ(gc.characters_at(sw.from), 1u);  // the kept slot
            const SurfaceView kept = gc.fade_surface(0);
            ASSERT_EQ(kept.level, sw.from);
            EXPECT_EQ(kept.positions.data(), left.positions.data());
            if (sw.from == kSkinned) {
                // The left mesh is the skinned level's linear-blend skin of this frame's pose (the pose is evaluated
                // every frame while fading), within float rounding.
                gc.reference_surface(w.draw_types()[0].poses, 0, kSkinned, reference);
                ASSERT_EQ(reference.size(), kept.positions.size());
                float worst = 0.0f;
                for (size_t i = 0; i < reference.size(); ++i) worst = std::max(worst, glm::length(reference[i] - kept.positions[i]));
                EXPECT_LT(worst, 1e-5f);
            }
        }
    }
    EXPECT_TRUE(w.render_status().ok()) << w.render_status().error().to_string();
    f.world.reset();
    f.renderer.reset();
    EXPECT_EQ(f.ctx->validation_message_count(), 0u);
}

// A character held at a drawn level (here pinned; in a crowd, by the resolver's hysteresis for 0.2 s after it
// leaves the view) is not drawn while its bounds lie wholly outside the view frustum: at the mesh, proxy
// and impostor levels alike, and it is drawn again once the view turns back.
TEST(WorldDrawLists, LeaveOutCharactersOutsideTheView) {
    Fixture f;
    if (!make(f)) return;
    World& w = *f.world;
    const glm::vec2 viewport(160.0f, 240.0f);
    for (const uint8_t level : {kSkinned, kProxy, kImpostor}) {
        SCOPED_TRACE("level " + std::to_string(level));
        w.set_view_override(std::nullopt, 50.0f, viewport);
        settle_at(w, level);
        const Drawn seen = drawn(w);
        EXPECT_GT(seen.meshes + seen.proxies + seen.impostors, 0u);
        // Far from the walker's circle about the origin and looking away from it: behind the camera.
        w.set_view_override(CameraKey{0.0f, glm::vec3(500.0f, 1.7f, 500.0f), glm::vec3(1000.0f, 1.7f, 1000.0f)}, 50.0f, viewport);
        w.step();
        EXPECT_EQ(w.explain(0)["attributes"]["visible"], false);
        EXPECT_EQ(w.runtime(0).geometry->level_of(0), level);  // still held at the level
        const Drawn away = drawn(w);
        EXPECT_EQ(away.meshes, 0u);
        EXPECT_EQ(away.proxies, 0u);
        EXPECT_EQ(away.impostors, 0u);
        w.set_view_override(std::nullopt, 50.0f, viewport);
        w.step();
        const Drawn back = drawn(w);
        EXPECT_EQ(back.meshes, seen.meshes);
        EXPECT_EQ(back.proxies, seen.proxies);
        EXPECT_EQ(back.impostors, seen.impostors);
    }
    EXPECT_TRUE(w.render_status().ok()) << w.render_status().error().to_string();
    f.world.reset();
    f.renderer.reset();
    EXPECT_EQ(f.ctx->validation_message_count(), 0u);
}

// Every mesh level of the character's type is registered with the renderer when the renderer is attached
// (DrawListBuilder::prepare): a frame where a level first appears registers nothing, so it uploads no texture and
// reorders no index list (on crowd_10k such frames took 10-25 ms of render_prepare per type, and up to 127 ms).
TEST(WorldDraws, MeshLevelsAreRegisteredWhenTheRendererIsAttachedNotAtFirstUse) {
    Fixture f;
    ASSERT_TRUE(make(f));
    World& w = *f.world;
    const GeometryController& gc = *w.runtime(0).geometry;
    size_t mesh_levels = 0;
    for (uint8_t l = 0; l < gc.level_count(); ++l) mesh_levels += drawn_as_mesh(gc.level(l).method);
    EXPECT_GE(mesh_levels, 4u) << "the default rules: subdivided, two layered and three skinned levels";
    const size_t registered = f.renderer->topology_count();
    EXPECT_EQ(registered, mesh_levels) << "one topology a mesh level of the one type, before any frame";
    for (const uint8_t level : {kSkinned, kLayeredLow, uint8_t(4), uint8_t(5), kLayeredHigh}) {
        SCOPED_TRACE("level " + std::to_string(level));
        settle_at(w, level);
        EXPECT_GT(drawn(w).meshes, 0u);
        EXPECT_EQ(f.renderer->topology_count(), registered) << "nothing registered in a frame";
    }
    f.world.reset();
    f.renderer.reset();
    EXPECT_EQ(f.ctx->validation_message_count(), 0u);
}

// A crowd with a height range plays only its variants; the base type it varies has no character, so it gets no
// impostor atlas (a bake of up to a second at load for nothing): one atlas per variant.
TEST(WorldDraws, OnlyTypesWithCharactersBakeImpostorAtlases) {
    Fixture f;
    ASSERT_TRUE(make(f, parse_scene(R"({"camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
        "crowds": [{"count": 4, "layout": "grid", "spacing": 2, "height": [1.6, 1.8], "variants": 2}]})",
                                    kData + "scenes/variants_inline.json")));
    World& w = *f.world;
    ASSERT_EQ(w.type_count(), 3u) << "the base type and its two variants";
    EXPECT_EQ(w.runtime(0).count, 0u);
    std::vector<std::string> baked;
    for (const World::ImpostorReport& a : w.impostor_atlases()) baked.push_back(a.type);
    EXPECT_EQ(baked, (std::vector<std::string>{w.type(1).name, w.type(2).name}));
    f.world.reset();
    f.renderer.reset();
    EXPECT_EQ(f.ctx->validation_message_count(), 0u);
}

// A character playing a walking clip with root motion (systems/motion/root_motion.hpp), drawn as an impostor, shows
// the walk rows of its atlas at the phase its stride gives, which runs on as it travels; with root motion off it
// does not travel and shows the standing row.
TEST(WorldDraws, AnImpostorCarriedByRootMotionWalks) {
    for (const bool root_motion : {true, false}) {
        SCOPED_TRACE(root_motion ? "root motion" : "no root motion");
        Fixture f;
        const std::string request = std::string(R"({"type": "play", "clip": "humanoid.walk_1.10", "root_motion": )") +
                                    (root_motion ? "true" : "false") + "}";
        ASSERT_TRUE(make(f, parse_scene(R"({"camera": {"position": [0, 2, 12], "target": [0, 1, 0]},
            "characters": [{"position": [0, 0, 0], "requests": [)" + request + "]}]}",
                                        kData + "scenes/root_motion_inline.json")));
        World& w = *f.world;
        ASSERT_TRUE(w.pin_geom_level(0, kImpostor).ok());
        std::vector<float> phases;
        for (int i = 0; i < 30; ++i) {
            w.step();
            ASSERT_TRUE(w.render_status().ok()) << w.render_status().error().to_string();
            ASSERT_EQ(w.render_lists().impostors.size(), 1u);
            phases.push_back(w.render_lists().impostors[0].forward_phase.z);
        }
        if (root_motion) {
            // Walking rows, phase in [0, 1), running on (at 1.10 m/s a cycle takes about a second: half a cycle here).
            for (size_t i = 5; i < phases.size(); ++i) {
                EXPECT_GE(phases[i], 0.0f) << "frame " << i;
                EXPECT_LT(phases[i], 1.0f) << "frame " << i;
            }
            float advanced = 0.0f;
            for (size_t i = 6; i < phases.size(); ++i) advanced += phases[i] - phases[i - 1] + (phases[i] < phases[i - 1] ? 1.0f : 0.0f);
            EXPECT_GT(advanced, 0.2f);
            EXPECT_LT(advanced, 0.8f);
        } else {
            for (size_t i = 5; i < phases.size(); ++i) EXPECT_EQ(phases[i], -1.0f) << "frame " << i;
        }
        f.world.reset();
        f.renderer.reset();
        EXPECT_EQ(f.ctx->validation_message_count(), 0u);
    }
}

// A camera straight above a character (a strategy game's) sees its impostor: the atlas's band of views from straight
// down (ImpostorBakeInput::elevations) faces it, where an upright quad was edge on and showed nothing (and before
// look_at_y_up the view itself was NaN). The impostor covers as many pixels as the character's skinned mesh within
// one pixel of the mesh's outline: at most as many pixels more or fewer as the mesh has on its edge (the atlas's
// texels are about a pixel at this size, and the skinned and the layered body it is baked from differ by less).
TEST(WorldDraws, ACameraStraightAboveSeesTheImpostorFromAbove) {
    Fixture f;
    ASSERT_TRUE(make(f, parse_scene(R"({"camera": {"position": [0, 5, 0], "target": [0, 0, 0]},
        "characters": [{"position": [0, 0, 0], "heading_deg": 30}]})",
                                    kData + "scenes/top_down_inline.json")));
    World& w = *f.world;
    struct Cover {
        double pixels = 0.0, edge = 0.0;  // the character's pixels; those of them beside a background pixel
    };
    const auto covered = [&](uint8_t level) {
        settle_at(w, level);
        EXPECT_TRUE(w.finish_rendering().ok());
        Result<gpu::Rgba8Image> image = f.target.read_back(*f.ctx);
        EXPECT_TRUE(image.ok());
        const std::vector<uint8_t>& px = image.value().pixels;
        const auto width = static_cast<int>(image.value().width), height = static_cast<int>(px.size() / 4) / width;
        // Pixels unlike the top-left one (the clear colour: the character is in the middle).
        const auto on = [&](int x, int y) {
            if (x < 0 || y < 0 || x >= width || y >= height) return false;
            const size_t i = 4 * (size_t(y) * size_t(width) + size_t(x));
            return px[i] != px[0] || px[i + 1] != px[1] || px[i + 2] != px[2];
        };
        Cover c;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (on(x, y)) {
                    c.pixels += 1.0;
                    c.edge += !on(x - 1, y) || !on(x + 1, y) || !on(x, y - 1) || !on(x, y + 1) ? 1.0 : 0.0;
                }
        return c;
    };
    const Cover mesh = covered(kSkinned), impostor = covered(kImpostor);
    EXPECT_EQ(drawn(w).impostors, 1u);
    EXPECT_GT(mesh.pixels, 300.0) << "the figure from 4 m above, at about 60 px a metre";
    EXPECT_NEAR(impostor.pixels, mesh.pixels, mesh.edge) << "the impostor's outline within a pixel of the mesh's";
    f.world.reset();
    f.renderer.reset();
    EXPECT_EQ(f.ctx->validation_message_count(), 0u);
}

}  // namespace
}  // namespace aloha
