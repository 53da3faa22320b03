// Motion files on a character type (CharacterTypeDesc::motions, host/scene/character_motions.hpp): a BVH in
// another naming convention and unit, and a glTF's animations, are retargeted onto the type's skeleton and
// played by their new names; what cannot be retargeted is an error naming the scene's JSON pointer or the file.
// With ../shared/assets (skipped when absent): the CMU 131_01 take onto the built-in humanoid and onto
// CesiumMan, each planted source ankle staying planted on the target.
#include "systems/motion/clip.hpp"
#include "systems/motion/library/motion_library.hpp"
#include "tests/common/bvh_writer.hpp"
#include "tests/common/clip_pose.hpp"
#include "tests/common/gltf_writer.hpp"
#include "tests/common/rig_fixtures.hpp"
#include "tests/common/test_assets.hpp"
#include "tests/host/scene/character_checks.hpp"

#include <cstdio>

namespace aloha {
namespace {

namespace fs = std::filesystem;
using namespace test;  // NOLINT: the character checks

CharacterTypeDesc builtin_type(const std::string& name) {
    CharacterTypeDesc d;
    d.name = name;
    d.humanoid = builtin_humanoid();
    d.scene_file = "test-scene.json";
    d.pointer = "/character_types/0";
    return d;
}

MotionFileDesc motion(const fs::path& file, const std::string& name = "") {
    MotionFileDesc m;
    (file.extension() == ".bvh" ? m.bvh : m.gltf) = file.string();
    m.name = name;
    m.pointer = "/character_types/0/motions/0";
    return m;
}

bool has_note(const CharacterType& t, const std::string& part) {
    for (const std::string& n : t.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

std::string error_of(const CharacterTypeDesc& d) {
    Result<CharacterType> t = load_character_type(d);
    return t.ok() ? std::string("(loaded)") : t.error().to_string();
}

// A type with walk loops of its own: they come first among its walk clips, and the generated gaits join them only
// beyond a quarter of their speeds (slower than the slowest / 1.25, faster than the fastest x 1.25), so a walk request
// there plays a generated gait, not its own loop warped; the note says which joined.
void expect_own_walk_first(const CharacterType& t, const std::string& name) {
    float slowest = 1e9f, fastest = 0.0f;
    size_t own = 0;
    for (; own < t.gait_clips.size() && t.clips.find(t.gait_clips[own])->name().rfind(name + ".loop", 0) == 0; ++own) {
        const float v = t.clips.find(t.gait_clips[own])->root_speed();
        slowest = std::min(slowest, v), fastest = std::max(fastest, v);
    }
    ASSERT_GE(own, 1u) << name << ": its own loops first";
    for (size_t g = own; g < t.gait_clips.size(); ++g) {
        const float v = t.clips.find(t.gait_clips[g])->root_speed();
        EXPECT_TRUE(v < slowest / 1.25f || v > fastest * 1.25f) << name << ": " << t.clips.find(t.gait_clips[g])->name() << " at " << v;
    }
    EXPECT_TRUE(has_note(t, "its own walk loops stay its walk with the gaits beyond their reach (" + name + ".walk_0.50")) << name;
    // The slowest generated walk that joined is what a request at its speed plays; at the own loops' speed, their own.
    MotionController mc(t.skeleton, t.clips, 1);
    mc.set_walk_clips(t.gait_clips);
    EXPECT_EQ(mc.pick_walk_clip(0.5f), find_clip(t, name + ".walk_0.50")) << name;
    EXPECT_EQ(mc.pick_walk_clip(fastest), static_cast<int>(t.gait_clips[own - 1])) << name;
}

TEST(CharacterMotions, PoserBvhInCentimetresPlaysOnTheBuiltInHumanoid) {
    const fs::path dir = temp_dir("motions_poser");
    RigStyle cm;
    cm.units_per_metre = 100.0f;
    // 40 frames at 30 fps, the root moving 4 cm a frame along +Z, every joint at rest.
    test::write_text((dir / "poser.bvh").string(), test::bvh_text(test::styled(test::renamed_humanoid(test::poser_names()), cm), 40, glm::vec3(0, 0, 1), 4.0f));
    CharacterTypeDesc d = builtin_type("h");
    d.motions = {motion(dir / "poser.bvh")};
    const CharacterType t = load_or_fail(d);
    const int id = find_clip(t, "h.poser");
    ASSERT_GE(id, 0) << "named by the file's stem after the type's prefix";
    const AnimationClip* clip = t.clips.find(static_cast<ClipId>(id));
    ASSERT_NE(clip, nullptr);
    EXPECT_NEAR(clip->duration(), 39.0f / 30.0f, 1e-5f);  // the text's frame time 0.0333333: 39 x 3.3e-8 s off
    // The fixture has the built-in humanoid's proportions at 1.75 m and so does the type: the pelvis travels the
    // file's 1.56 m (39 frames of 4 cm) times k = 1, within the text's 6 significant digits (5e-6 relative: 8e-6 m
    // over the travel, 1e-5 allowed) and the stored clip's quantisation at both ends (measured: 2.4e-7 m).
    EXPECT_NEAR(clip->root_end().z - clip->root_start().z, 1.56f, 1e-5f + 2.0f * clip->error_bound().translation);
    EXPECT_NEAR(clip->root_end().x - clip->root_start().x, 0.0f, 2.0f * clip->error_bound().translation);
    EXPECT_TRUE(has_note(t, "clip 'h.poser' retargeted from poser.bvh (pelvis travel x1.0"));
}

TEST(CharacterMotions, GltfAnimationsByNameAndErrors) {
    const fs::path dir = temp_dir("motions_gltf");
    // A Rigify glTF with one animation, "sway".
    test::write_text((dir / "rigify.gltf").string(), test::gltf_text(test::renamed_humanoid(test::rigify_names("DEF-")), 1, 0.3f));
    CharacterTypeDesc d = builtin_type("h");
    d.motions = {motion(dir / "rigify.gltf")};
    const CharacterType t = load_or_fail(d);
    EXPECT_GE(find_clip(t, "h.sway"), 0) << "a glTF animation keeps its name";

    // The same skeleton and animation in an animation file (no skin, no mesh), as Blender exports an armature alone.
    nlohmann::json bare = nlohmann::json::parse(test::gltf_text(test::renamed_humanoid(test::rigify_names("DEF-")), 1, 0.3f));
    bare.erase("skins");
    for (auto& node : bare["nodes"]) node.erase("skin");
    test::write_text((dir / "armature.gltf").string(), bare.dump());
    CharacterTypeDesc from_bare = builtin_type("h");
    from_bare.motions = {motion(dir / "armature.gltf")};
    EXPECT_GE(find_clip(load_or_fail(from_bare), "h.sway"), 0) << "an animation file is a motion file";

    d.motions[0].clip = "run";
    EXPECT_NE(error_of(d).find("no animation 'run' in"), std::string::npos) << error_of(d);
    EXPECT_NE(error_of(d).find("(it has 'sway')"), std::string::npos) << error_of(d);
    EXPECT_NE(error_of(d).find("/character_types/0/motions/0/clip"), std::string::npos) << error_of(d);

    d.motions[0].clip = "sway";
    d.motions[0].name = "idle";  // the built-in library's h.idle
    EXPECT_NE(error_of(d).find("clip 'h.idle' already exists on type 'h' (give the motion another 'name')"), std::string::npos) << error_of(d);

    // A motion whose skeleton is no humanoid.
    test::write_text((dir / "dog.bvh").string(), test::bvh_text(test::quadruped(), 30, glm::vec3(0, 0, 1), 3.0f));
    d.motions = {motion(dir / "dog.bvh")};
    EXPECT_NE(error_of(d).find("dog.bvh: the motion's skeleton is not a humanoid"), std::string::npos) << error_of(d);

    // A type that is no humanoid cannot take motion files.
    CharacterTypeDesc dog = desc_for("dog", (dir / "dog.bvh").string());
    dog.motions = {motion(dir / "rigify.gltf")};
    EXPECT_NE(error_of(dog).find("type 'dog' is not a mapped humanoid"), std::string::npos) << error_of(dog);
    EXPECT_NE(error_of(dog).find("/character_types/0/motions"), std::string::npos) << error_of(dog);

    // A motion file that is missing names itself.
    d.motions = {motion(dir / "missing.bvh")};
    EXPECT_NE(error_of(d).find("missing.bvh"), std::string::npos) << error_of(d);
}

// The Unreal mannequin's layout: a "root" joint on the ground above the pelvis, in centimetres, Z-up facing +X.
RawSkeleton unreal_rooted() {
    const RawSkeleton body = test::renamed_humanoid(test::unreal_names());
    RawSkeleton raw;
    raw.joints.push_back(RawJoint{"root", -1, glm::vec3(0.0f)});
    for (RawJoint j : body.joints) {
        j.parent += 1;  // the old root (pelvis) hangs under "root" at its model position
        raw.joints.push_back(j);
    }
    test::RigStyle unreal;
    unreal.units_per_metre = 100.0f;
    unreal.axes = glm::angleAxis(2.0943951f, glm::normalize(glm::vec3(1, 1, 1)));  // +Y -> +Z, +Z -> +X
    unreal.bone_frames = true;
    return test::styled(raw, unreal);
}

// The built-in humanoid's generated 1.40 m/s walk, three cycles written as a CMU-named BVH in centimetres at 60 fps,
// given with "walk" to a Rigify glTF in a T-pose and to an Unreal-rooted glTF: it is cut to a loop and becomes each
// type's clip walk, which walks with planted ankles within the bar expect_walks holds the kinematic walk to (1 cm).
// On the Unreal rig the root joint carries the travel (joint 0 is what the motion system moves the character by).
TEST(CharacterMotions, WalkTakeBecomesTheTypesClipWalk) {
    const fs::path dir = temp_dir("motions_walk");
    const Skeleton body = humanoid_skeleton_for({1.62f, 0.3f});
    const MotionLibrary lib = make_motion_library(body, humanoid_rig(body), "src");
    const AnimationClip walk = build_clip(lib.gaits[3], body, ClipEncoding::Float32).value();
    test::write_text((dir / "walk.bvh").string(), test::bvh_text_of_clip(body, walk, 100.0f, 60.0f, 3));
    RigStyle t_pose;
    t_pose.t_pose = true;
    test::write_text((dir / "rig.gltf").string(), test::gltf_text(test::styled(test::renamed_humanoid(test::rigify_names("DEF-"), {}, true), t_pose), 1, 0.3f));
    test::write_text((dir / "unreal.gltf").string(), test::gltf_text(unreal_rooted(), 2, 0.3f));
    for (const char* name : {"rig", "unreal"}) {
        CharacterTypeDesc d = desc_for(name, (dir / (std::string(name) + ".gltf")).string());
        d.motions = {motion(dir / "walk.bvh")};
        d.motions[0].walk = true;
        const CharacterType t = load_or_fail(d);
        ASSERT_GE(t.gait_clips.size(), 1u) << name;
        EXPECT_EQ(find_clip(t, std::string(name) + ".loop"), static_cast<int>(t.gait_clips[0])) << "its own 'sway' does not loop; the take does";
        EXPECT_TRUE(has_note(t, "walk loop '" + std::string(name) + ".loop' cut from '" + name + ".walk'"));
        expect_own_walk_first(t, name);
        ASSERT_TRUE(t.rig.has_value());
        const float speed = t.clips.find(t.gait_clips[0])->root_speed();
        EXPECT_GT(speed, 1.0f) << name;
        expect_clip_walk(t, speed, std::string(name) + ": retargeted walk loop");
    }

    // A take that does not loop cannot be the walk: an error at the motion's "walk".
    CharacterTypeDesc d = desc_for("rig", (dir / "rig.gltf").string());
    d.motions = {motion(dir / "still.bvh")};
    d.motions[0].walk = true;
    test::write_text(d.motions[0].bvh, test::bvh_text(test::renamed_humanoid(test::poser_names()), 30, glm::vec3(0, 0, 1), 0.0f));
    EXPECT_NE(error_of(d).find("/character_types/0/motions/0/walk: 'walk': clip 'rig.still' cannot be the type's walk"), std::string::npos) << error_of(d);
}

// The built-in humanoid's gait with its root's horizontal travel taken out when `in_place` (an "In Place" export),
// played backwards when `backwards`.
RawAnimation take_of(const RawAnimation& gait, bool in_place, bool backwards = false) {
    RawAnimation out = gait;
    if (in_place)
        for (glm::vec3& p : out.tracks[0].translations.values) p.x = 0.0f, p.z = 0.0f;
    if (backwards)
        for (RawJointTracks& t : out.tracks) {
            auto flip = [&](auto& track) {
                std::reverse(track.values.begin(), track.values.end());
                std::reverse(track.times.begin(), track.times.end());
                for (float& time : track.times) time = gait.duration - time;
            };
            flip(t.translations);
            flip(t.rotations);
            flip(t.scales);
        }
    return out;
}

// One cycle of `take` as a BVH in centimetres at 60 fps.
std::string bvh_of(const Skeleton& body, const RawAnimation& take) {
    return test::bvh_text_of_clip(body, build_clip(take, body, ClipEncoding::Float32).value(), 100.0f, 60.0f, 1);
}

// An "In Place" walk and run (the built-in 1.40 m/s walk and 2.60 m/s run, their root's travel taken out, one cycle
// each), given with "walk" to a T-posed Rigify glTF: each gets root motion from its feet and becomes one of the
// type's walk clips, walked at the clip level with planted ankles (drift under 1 cm, the bar of every clip walk) at
// its speed, the generated gaits stepping aside. The same walk as a BVH type's own take is that type's walk. Played
// backwards it is no walk: an error at the motion's "walk" saying why.
TEST(CharacterMotions, InPlaceWalkAndRunGetRootMotionFromTheirFeet) {
    const fs::path dir = temp_dir("motions_in_place");
    const Skeleton body = humanoid_skeleton_for({1.75f, 0.5f});
    const MotionLibrary lib = make_motion_library(body, humanoid_rig(body), "src");
    test::write_text((dir / "walk_ip.bvh").string(), bvh_of(body, take_of(lib.gaits[3], true)));
    test::write_text((dir / "run_ip.bvh").string(), bvh_of(body, take_of(lib.gaits[6], true)));
    test::write_text((dir / "back_ip.bvh").string(), bvh_of(body, take_of(lib.gaits[3], true, true)));
    RigStyle t_pose;
    t_pose.t_pose = true;
    test::write_text((dir / "rig.gltf").string(), test::gltf_text(test::styled(test::renamed_humanoid(test::rigify_names("DEF-"), {}, true), t_pose), 1, 0.3f));
    CharacterTypeDesc d = desc_for("rig", (dir / "rig.gltf").string());
    d.motions = {motion(dir / "walk_ip.bvh"), motion(dir / "run_ip.bvh")};
    for (MotionFileDesc& m : d.motions) m.walk = true;
    const CharacterType t = load_or_fail(d);
    ASSERT_GE(t.gait_clips.size(), 2u);
    EXPECT_EQ(find_clip(t, "rig.loop"), static_cast<int>(t.gait_clips[0])) << "the walk";
    EXPECT_EQ(find_clip(t, "rig.loop2"), static_cast<int>(t.gait_clips[1])) << "the run";
    EXPECT_TRUE(has_note(t, "walk loop 'rig.loop' cut from 'rig.walk_ip'")) << t.notes.back();
    EXPECT_TRUE(has_note(t, "in place: root motion from its feet, 1.40 m/s forward"));
    expect_own_walk_first(t, "rig");
    for (size_t g = 0; g < 2; ++g) expect_clip_walk(t, t.clips.find(t.gait_clips[g])->root_speed(), "in-place take given root motion by its feet");

    const CharacterType own = load_or_fail(desc_for("ip", (dir / "walk_ip.bvh").string()));
    ASSERT_GE(own.gait_clips.size(), 1u);
    EXPECT_EQ(find_clip(own, "ip.loop"), static_cast<int>(own.gait_clips[0])) << "a BVH type's in-place take is its walk";
    expect_own_walk_first(own, "ip");
    // The gait's 1.40 m/s back from its feet, through a BVH's 9 digits at the gait's own 60 Hz frames: a regression
    // guard (measured 1.39999 m/s).
    EXPECT_NEAR(own.clips.find(own.gait_clips[0])->root_speed(), 1.4f, 1e-4f);

    d.motions = {motion(dir / "back_ip.bvh")};
    d.motions[0].walk = true;
    EXPECT_NE(error_of(d).find("/character_types/0/motions/0/walk: 'walk': clip 'rig.back_ip' cannot be the type's walk: clip "
                               "'rig.back_ip': its feet carry the body forward at -1.4"),
              std::string::npos)
        << error_of(d);
}

// A game pack's character file: the built-in humanoid with animations "WalkBack" (a walk travelling backwards),
// "Idle", "Walk" and "Run" (in place) in one glTF. Every animation is tried as a walk: "Walk" and "Run" become the
// type's walk clips, given root motion by their feet; "WalkBack" and "Idle" are none, and say nothing while
// another walks; "Idle" is what the type idles in. A file with only "WalkBack" and idles walks the generated gaits,
// one note giving the first's reason, and idles in the one named "idle" in any case ("IDLE" before "Idle_to_Run" and
// "Standing_Idle").
TEST(CharacterMotions, EveryAnimationOfAFileIsTriedAsAWalk) {
    const fs::path dir = temp_dir("motions_pack");
    const Skeleton body = humanoid_skeleton_for({1.75f, 0.5f});
    const MotionLibrary lib = make_motion_library(body, humanoid_rig(body), "src");
    auto built = [&](const RawAnimation& raw) { return build_clip(raw, body, ClipEncoding::Float32).value(); };
    const AnimationClip back = built(take_of(lib.gaits[3], false, true)), idle = built(lib.idle), walk = built(take_of(lib.gaits[3], true)),
                        run = built(take_of(lib.gaits[6], true));
    test::write_gltf_with_clips((dir / "pack.gltf").string(), body, {{"WalkBack", &back}, {"Idle", &idle}, {"Walk", &walk}, {"Run", &run}});
    const CharacterType t = load_or_fail(desc_for("pack", (dir / "pack.gltf").string()));
    ASSERT_GE(t.gait_clips.size(), 2u);
    EXPECT_EQ(find_clip(t, "pack.loop"), static_cast<int>(t.gait_clips[0])) << "Walk";
    EXPECT_EQ(find_clip(t, "pack.loop2"), static_cast<int>(t.gait_clips[1])) << "Run";
    expect_own_walk_first(t, "pack");
    EXPECT_TRUE(has_note(t, "walk loop 'pack.loop' cut from 'Walk'"));
    EXPECT_TRUE(has_note(t, "walk loop 'pack.loop2' cut from 'Run'"));
    EXPECT_TRUE(has_note(t, "in place: root motion from its feet, 2.5"));  // the run: 2.58 m/s, its flight bridged
    EXPECT_FALSE(has_note(t, "no clip walk"));
    // Resampled at 60 Hz over a cycle that is not a whole number of the file's 1/60 s keys, the foot between two keys
    // is a lerp, not planted: a regression guard (measured 1.39963 m/s).
    EXPECT_NEAR(t.clips.find(t.gait_clips[0])->root_speed(), 1.4f, 1e-3f);
    EXPECT_EQ(t.idle_clip, find_clip(t, "Idle")) << "the file's own idle, not the generated one";
    EXPECT_TRUE(has_note(t, "idle: the file's clip 'Idle'"));

    // The scene's "walks" picks: only "Run" is its walk; a named animation that does not walk, or is not in the file,
    // is an error at its place in "walks".
    CharacterTypeDesc chosen = desc_for("pack", (dir / "pack.gltf").string());
    chosen.walks = {"Run"};
    const CharacterType run_only = load_or_fail(chosen);
    ASSERT_GE(run_only.gait_clips.size(), 1u);
    EXPECT_TRUE(has_note(run_only, "walk loop 'pack.loop' cut from 'Run'"));
    EXPECT_FALSE(has_note(run_only, "cut from 'Walk'"));
    chosen.walks = {"Run", "Idle"};
    EXPECT_NE(error_of(chosen).find("test-scene.json: /character_types/0/walks/1: 'Idle' cannot be a walk: clip 'Idle': its feet carry the body forward"),
              std::string::npos)
        << error_of(chosen);
    chosen.walks = {"Jog"};
    EXPECT_NE(error_of(chosen).find("/character_types/0/walks/0: no animation 'Jog' in"), std::string::npos) << error_of(chosen);
    EXPECT_NE(error_of(chosen).find("(it has 'WalkBack', 'Idle', 'Walk', 'Run')"), std::string::npos) << error_of(chosen);

    test::write_gltf_with_clips((dir / "still.gltf").string(), body,
                                {{"WalkBack", &back}, {"Standing_Idle", &idle}, {"IDLE", &idle}, {"Idle_to_Run", &idle}});
    const CharacterType still = load_or_fail(desc_for("still", (dir / "still.gltf").string()));
    EXPECT_EQ(still.gait_clips.size(), std::size(kLibraryGaitSpeeds)) << "the generated gaits";
    EXPECT_EQ(still.idle_clip, find_clip(still, "IDLE")) << "named idle, before names starting or containing it";
    EXPECT_TRUE(has_note(still, "no clip walk: clip 'WalkBack' travels more than 45 degrees away from where the body faces (a backward or "
                                "sideways step): no walk (nor do its 3 other clips)"))
        << still.notes[0];
}

// A Mixamo-style animation file: joints in centimetres under an "Armature" node scaling by 0.01 and turning the rig
// Z-up, no skin, no mesh. The Armature node is then a joint of the skeleton (nothing folds it), which normalisation
// reads in metres and turns upright; the take, at rest in its first key, stands the built-in humanoid at its own rest
// hips height (within 0.5 mm; k = 1 within the fixture's rounding: the fixture has the built-in proportions).
TEST(CharacterMotions, MixamoAnimationFileUnderAnArmatureNode) {
    const fs::path dir = temp_dir("motions_mixamo");
    RigStyle cm;
    cm.units_per_metre = 100.0f;
    cm.bone_frames = true;
    nlohmann::json j = nlohmann::json::parse(test::gltf_text(test::styled(test::renamed_humanoid(test::mixamo_names()), cm), 1, 0.3f));
    const glm::quat z_up = glm::angleAxis(1.5707963f, glm::vec3(1, 0, 0));
    j["nodes"].push_back({{"name", "Armature"}, {"children", {0}}, {"scale", {0.01, 0.01, 0.01}}, {"rotation", {z_up.x, z_up.y, z_up.z, z_up.w}}});
    j["scenes"][0]["nodes"] = {j["nodes"].size() - 1};
    j.erase("skins");
    for (auto& node : j["nodes"]) node.erase("skin");
    test::write_text((dir / "mixamo_anim.gltf").string(), j.dump());
    CharacterTypeDesc d = builtin_type("h");
    d.motions = {motion(dir / "mixamo_anim.gltf", "sway")};
    const CharacterType t = load_or_fail(d);
    const int id = find_clip(t, "h.sway");
    ASSERT_GE(id, 0);
    const AnimationClip& clip = *t.clips.find(static_cast<ClipId>(id));
    const float rest_hips = t.skeleton.rest_translations()[static_cast<size_t>(t.map.find("Hips"))].y;
    // Measured 2.0e-4 m: the take's sway moves its lowest joint over the clip (the ground the heights are measured
    // from) and k is 1 to the fixture's rounding. A regression guard, not a derived bound.
    EXPECT_NEAR(clip.root_start().y, rest_hips, 5e-4f) << "the take's rest pose stands the body at its own hips height";
    EXPECT_NEAR(glm::length(glm::vec2(clip.root_start().x, clip.root_start().z)), 0.0f, 1e-5f);  // measured 1.8e-7
    EXPECT_TRUE(has_note(t, "clip 'h.sway' retargeted from mixamo_anim.gltf (pelvis travel x1.0")) << t.notes.back();
}

// Largest horizontal distance a target ankle moves between keys where the source's ankle moves under 1 mm, over
// k times the source's own move there (0: every planted source foot is planted on the target).
float planted_excess(const CharacterType& source, int source_clip, const CharacterType& target, int target_clip, float k) {
    const AnimationClip& a = *source.clips.find(static_cast<ClipId>(source_clip));
    const AnimationClip& b = *target.clips.find(static_cast<ClipId>(target_clip));
    auto ankles = [](const CharacterType& type, const AnimationClip& clip, float t) {
        const std::vector<glm::vec3> pos = clip_model_positions(clip, type.skeleton, t);
        return std::array<glm::vec3, 2>{pos[static_cast<size_t>(type.map.find("LeftAnkle"))], pos[static_cast<size_t>(type.map.find("RightAnkle"))]};
    };
    float worst = 0.0f;
    std::array<glm::vec3, 2> last_a{}, last_b{};
    for (int i = 0; i <= static_cast<int>(a.duration() * 120.0f); ++i) {
        const float t = static_cast<float>(i) / 120.0f;
        const auto pa = ankles(source, a, t), pb = ankles(target, b, t);
        for (size_t s = 0; s < 2 && i > 0; ++s) {
            const float moved_a = glm::length(glm::vec2(pa[s].x - last_a[s].x, pa[s].z - last_a[s].z));
            const float moved_b = glm::length(glm::vec2(pb[s].x - last_b[s].x, pb[s].z - last_b[s].z));
            if (moved_a < 1e-3f) worst = std::max(worst, moved_b - k * moved_a);
        }
        last_a = pa;
        last_b = pb;
    }
    return worst;
}

TEST(CharacterMotions, CmuTakeOntoTheBuiltInHumanoidAndCesiumMan) {
    ALOHA_REQUIRE_TEST_ASSET(bvh, "131_01.bvh");
    ALOHA_REQUIRE_TEST_ASSET(glb, "CesiumMan.glb");
    const CharacterType cmu = load_or_fail(desc_for("cmu", bvh));
    CharacterTypeDesc h = builtin_type("h");
    h.motions = {motion(bvh, "take")};
    CharacterTypeDesc cesium = desc_for("cesium", glb);
    cesium.humanoid_map = cesium_man_humanoid_map();
    cesium.motions = {motion(bvh, "take")};
    for (const CharacterTypeDesc* d : {&h, &cesium}) {
        const CharacterType t = load_or_fail(*d);
        const int id = find_clip(t, d->name + ".take");
        ASSERT_GE(id, 0);
        float k = 0.0f;
        for (const std::string& n : t.notes)
            if (std::sscanf(n.c_str(), ("clip '" + d->name + ".take' retargeted from 131_01.bvh (pelvis travel x%f").c_str(), &k) == 1) break;
        ASSERT_GT(k, 0.0f) << "the note gives the pelvis travel's scale";
        // The source's planted ankles (under 1 mm a key at 120 Hz) against the target's.
        const float excess = planted_excess(cmu, cmu.mocap_clip, t, id, k);
        // Both clips are stored quantised (ClipErrorBound): an ankle sampled from one is off by at most the root's
        // translation bound (per component: x sqrt 3) plus the rotation bound times the lever from the pelvis to the
        // ankle (under the leg's length, 1.1 m on either body), and a move between two samples by twice that.
        auto ankle_bound = [](const AnimationClip& c) { return c.error_bound().translation * std::sqrt(3.0f) + c.error_bound().rotation * 1.1f; };
        const float bound = 2.0f * ankle_bound(*t.clips.find(static_cast<ClipId>(id))) +
                            2.0f * k * ankle_bound(*cmu.clips.find(static_cast<ClipId>(cmu.mocap_clip)));
        std::printf("[figure] 131_01 onto %s: pelvis travel x%.3f, planted-ankle excess %.2e m (quantisation bound %.2e m)\n", d->name.c_str(),
                    static_cast<double>(k), static_cast<double>(excess), static_cast<double>(bound));
        EXPECT_LT(excess, bound);
        EXPECT_FALSE(has_note(t, "fall short")) << "lowering the pelvis lets the legs reach every key";
    }
}

}  // namespace
}  // namespace aloha
