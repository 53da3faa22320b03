// Runs the built `aloha` program end to end (headless, lavapipe) and checks its outputs and errors.
#include "engine/anim/humanoid_map.hpp"
#include "systems/geometry/controller/bake_code_digest.hpp"
#include "systems/geometry/controller/skin_bake.hpp"
#include "systems/render/far_layer.hpp"
#include "tests/common/rig_fixtures.hpp"
#include "tests/host/tool/tool_run.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using aloha::test::RunResult;
using aloha::test::run;

const std::string kScenes = std::string(ALOHA_SOURCE_DIR) + "/data/scenes/";

fs::path temp_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("aloha_tool_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

TEST(Tool, ProfileWritesEveryReport) {
    const fs::path out = temp_dir("profile");
    const RunResult r = run("profile " + kScenes + "crowd_1k.json --frames 6 --warmup 2 --characters 200 --quiet "
                            "--validation --out " + (out / "p").string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* f : {"report.json", "frames.csv", "trace.json", "frame_times.svg", "last_frame.png"})
        EXPECT_TRUE(fs::exists(out / "p" / f)) << f;
    std::ifstream in(out / "p" / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["characters"], 200);
    EXPECT_EQ(report["frames"], 6);
    for (const char* k : {"mean", "p50", "p95", "p99", "max"}) {
        EXPECT_TRUE(report["cpu_systems_ms"].contains(k));
        EXPECT_TRUE(report["systems"]["lod_rules"].contains(k));
    }
    EXPECT_EQ(report["characters_per_level_per_frame"].size(), 6u);
    // The switch-hitch reading covers every measured frame, split by whether a level changed in it.
    const nlohmann::json& hitch = report["switch_hitch"];
    EXPECT_EQ(hitch["all"]["frames"].get<size_t>(), 6u);
    EXPECT_EQ(hitch["with_switch"]["frames"].get<size_t>() + hitch["without_switch"]["frames"].get<size_t>(), 6u);
    EXPECT_DOUBLE_EQ(hitch["p95_ms"].get<double>(), report["cpu_systems_ms"]["p95"].get<double>());
    // The geometric controllers' work over the measured frames, one entry per geometric level: every
    // character drawn by a level was updated there once a frame (at most 200 x 6 updates in all).
    const nlohmann::json& work = report["geometry_work"];
    ASSERT_EQ(work.size(), report["levels"]["geometric"].size());
    uint64_t updated = 0;
    for (const auto& level : work) {
        for (const char* k : {"characters_updated", "springs_stepped", "skin_vertices", "per_frame"}) EXPECT_TRUE(level.contains(k)) << k;
        updated += level["characters_updated"].get<uint64_t>();
    }
    EXPECT_GT(updated, 0u);
    EXPECT_LE(updated, 200u * 6u);
    // frames.csv: a header of distinct column names (per-system columns apart from the totals), then
    // one row per measured frame with as many fields.
    std::ifstream csv(out / "p" / "frames.csv");
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(csv, line);) {
        std::vector<std::string> fields;
        std::stringstream ss(line);
        for (std::string field; std::getline(ss, field, ',');) fields.push_back(field);
        rows.push_back(std::move(fields));
    }
    ASSERT_EQ(rows.size(), 7u);
    const std::set<std::string> columns(rows[0].begin(), rows[0].end());
    EXPECT_EQ(columns.size(), rows[0].size()) << "duplicate column names";
    EXPECT_TRUE(columns.count("render_ms") && columns.count("system_render_ms") && columns.count("system_motion_ms"));
    for (const auto& row : rows) EXPECT_EQ(row.size(), rows[0].size());
    // trace.json: one track per system, and per worker thread that ran a system's parallel work.
    std::ifstream trace(out / "p" / "trace.json");
    const nlohmann::json t = nlohmann::json::parse(trace);
    EXPECT_FALSE(t["traceEvents"].empty());
    std::set<std::string> tracks;
    for (const auto& e : t["traceEvents"])
        if (e["name"] == "thread_name") tracks.insert(e["args"]["name"].get<std::string>());
    for (const char* track : {"system: lod_attributes", "system: motion", "system: muscle", "system: spring_skin", "system: render", "worker 0"})
        EXPECT_TRUE(tracks.count(track)) << track;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    // What the renderer drew with, each default resolved for the device (lavapipe here: the far layer, nearest mips and
    // impostor views), printed and in the report; a second run's options show there.
    const nlohmann::json& drawn = report["renderer"];
    EXPECT_EQ(drawn["far_layer_px"].get<double>(), double(aloha::kDefaultFarLayerBelowPx));
    EXPECT_EQ(drawn["texture_mips"], "nearest");
    EXPECT_EQ(drawn["impostor_views"], "nearest");
    EXPECT_EQ(drawn["impostor_elevations"], 3);
    EXPECT_NE(r.output.find("renderer: far layer under " + std::to_string(int(aloha::kDefaultFarLayerBelowPx)) + " px"), std::string::npos)
        << r.output;
    const RunResult chosen = run("profile " + kScenes + "crowd_1k.json --frames 1 --warmup 0 --characters 20 --quiet --far-layer 0 "
                                 "--impostor-views pick --texture-mips blend --out " + (out / "chosen").string());
    ASSERT_EQ(chosen.code, 0) << chosen.output;
    std::ifstream chosen_in(out / "chosen" / "report.json");
    const nlohmann::json chosen_report = nlohmann::json::parse(chosen_in);
    EXPECT_EQ(chosen_report["renderer"]["far_layer_px"].get<double>(), 0.0);
    EXPECT_EQ(chosen_report["renderer"]["impostor_views"], "pick");
    EXPECT_EQ(chosen_report["renderer"]["texture_mips"], "blend");
    EXPECT_NE(chosen.output.find("renderer: far layer off"), std::string::npos) << chosen.output;
    // A second run refuses to overwrite the reports without --force.
    const RunResult again = run("profile " + kScenes + "crowd_1k.json --frames 2 --characters 50 --quiet --out " + (out / "p").string());
    EXPECT_NE(again.code, 0);
    EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
    fs::remove_all(out);
}

// --constant-fragments (the fragment cost alone) under validation: the constant shader's interface matches the vertex
// shader's outputs, so the validation layers have nothing to say; the report records it.
TEST(Tool, ProfileConstantFragmentsPassesValidation) {
    const fs::path out = temp_dir("profile_constant");
    const RunResult r = run("profile " + kScenes + "closeup.json --frames 2 --warmup 0 --constant-fragments --quiet --validation "
                            "--out " + (out / "p").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("alidation"), std::string::npos) << r.output;
    std::ifstream in(out / "p" / "report.json");
    EXPECT_EQ(nlohmann::json::parse(in)["renderer"]["constant_fragments"], true);
    fs::remove_all(out);
}

// --fidelity waits for every frame (its probe reads each one back and draws its reference with the same
// renderer), so the default --gpu-overlap auto runs serially and the report says so.
TEST(Tool, ProfileFidelityRunsEveryFrameSerially) {
    const fs::path out = temp_dir("profile_fidelity");
    const RunResult r = run("profile " + kScenes + "closeup.json --frames 4 --warmup 1 --fidelity --quiet --validation --out " +
                            (out / "p").string());
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(out / "p" / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["gpu_overlap"]["mode"], "off");
    EXPECT_EQ(report["gpu_overlap"]["frames_overlapped"], 0);
    EXPECT_EQ(report["fidelity"]["psnr_db"]["count"], 4);
    // Silhouettes: the close-up's one character, drawn where the reference draws it.
    const nlohmann::json& silhouettes = report["fidelity"]["silhouettes"];
    EXPECT_EQ(silhouettes["pixels_over_reference"]["count"], 4);
    EXPECT_GT(silhouettes["reference_covered_within_1px"]["min"].get<double>(), 0.9);
    EXPECT_GT(silhouettes["drawn_on_reference_within_1px"]["min"].get<double>(), 0.9);
    EXPECT_NE(r.output.find("fidelity silhouettes:"), std::string::npos) << r.output;
    // The default rules' level 0 has fat springs, so the deviation against the moving body is measured on
    // every frame, as the literal one is (null would mean a frame's mesh vertices had no reference springs).
    EXPECT_EQ(report["fidelity"]["mean_moving_reference_deviation_px"]["count"], 4);
    // The detrended whole-frame comparison: 3 compared frames, of which the first and last cannot be centred.
    const nlohmann::json& detrended = report["fidelity"]["popping"]["detrended"];
    EXPECT_EQ(detrended["switch_frames"].get<size_t>() + detrended["ordinary_frames"].get<size_t>(), 1u);
    EXPECT_NE(r.output.find("detrended"), std::string::npos) << r.output;
    // The error-change reading compares every frame after the first, and frames.csv carries its column.
    const nlohmann::json& against = report["fidelity"]["popping"]["against_reference"];
    EXPECT_EQ(against["switch_frames"].get<size_t>() + against["ordinary_frames"].get<size_t>(), 3u);
    EXPECT_NE(r.output.find("fidelity against the reference"), std::string::npos) << r.output;
    // The control reads the same frames on the reference picture's own change.
    const nlohmann::json& control = report["fidelity"]["popping"]["control"];
    EXPECT_EQ(control["switch_frames"].get<size_t>() + control["ordinary_frames"].get<size_t>(), 3u);
    EXPECT_NE(r.output.find("fidelity control"), std::string::npos) << r.output;
    std::ifstream csv(out / "p" / "frames.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_NE(header.find(",error_change,error_change_in_switches,reference_change"), std::string::npos) << header;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    fs::remove_all(out);
}

// Impostor atlases in the bake cache: a first run bakes every type's atlas and saves it, a second run over the same
// cache directory reads each one back, and the two runs end in the same state and the same picture.
TEST(Tool, ProfileReadsImpostorAtlasesBackFromTheBakeCache) {
    const fs::path out = temp_dir("profile_atlas_cache");
    const std::string common = "profile " + kScenes + "crowd_1k.json --frames 3 --warmup 2 --characters 60 --quiet --validation " +
                               "--cache-dir " + (out / "cache").string() + " --out ";
    nlohmann::json reports[2];
    for (int i = 0; i < 2; ++i) {
        const RunResult r = run(common + (out / std::to_string(i)).string());
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(i == 0 ? "ms to bake" : "ms from the bake cache"), std::string::npos) << r.output;
        std::ifstream in(out / std::to_string(i) / "report.json");
        reports[i] = nlohmann::json::parse(in);
        ASSERT_FALSE(reports[i]["impostor_atlases"].empty());
        for (const auto& atlas : reports[i]["impostor_atlases"]) {
            // A variant drawing another's atlas scaled (--impostor-share) bakes nothing and reads nothing.
            const bool own = atlas["shared_from"].get<std::string>().empty();
            EXPECT_EQ(atlas["cached"].get<bool>(), own && i == 1) << atlas.dump();
            EXPECT_EQ(atlas["texture_bytes"].get<uint64_t>() > 0, own) << atlas.dump();
        }
    }
    ASSERT_EQ(reports[0]["impostor_atlases"].size(), reports[1]["impostor_atlases"].size());
    for (size_t a = 0; a < reports[0]["impostor_atlases"].size(); ++a)
        for (const char* key : {"type", "shared_from", "scale", "distance_px"})
            EXPECT_EQ(reports[0]["impostor_atlases"][a][key], reports[1]["impostor_atlases"][a][key]) << key << ": the same shares";
    EXPECT_EQ(reports[0]["state_hash"], reports[1]["state_hash"]);
    // The bake cache's report: the first run wrote what the second read.
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(reports[i]["bake_cache"].is_object()) << reports[i]["bake_cache"].dump();
    EXPECT_EQ(reports[0]["bake_cache"]["directory"], (out / "cache").string());
    EXPECT_GT(reports[0]["bake_cache"]["writes"].get<int>(), 0);
    EXPECT_GT(reports[1]["bake_cache"]["hits"].get<int>(), 0);
    EXPECT_EQ(reports[1]["bake_cache"]["writes"].get<int>(), 0) << "nothing baked again";
    // The version is the library's source digest and shared libraries' ids, not the program's own build-id: this test
    // program, another executable linked with the same library, reads and writes the same entries.
    const aloha::Result<std::vector<uint8_t>> version = aloha::skin_bake_code_version();
    ASSERT_TRUE(version.ok()) << version.error().to_string();
    std::string hex;
    for (const uint8_t b : version.value()) {
        char h[3];
        std::snprintf(h, sizeof(h), "%02x", b);
        hex += h;
    }
    EXPECT_EQ(reports[1]["bake_cache"]["code_version"].get<std::string>(), hex);
    const std::string version_bytes(version.value().begin(), version.value().end());
    EXPECT_NE(version_bytes.find(aloha::kBakeCodeDigest), std::string::npos) << "the digest is part of the version";
    const auto bytes = [](const fs::path& p) {
        std::ifstream f(p, std::ios::binary);
        return std::vector<char>(std::istreambuf_iterator<char>(f), {});
    };
    EXPECT_EQ(bytes(out / "0" / "last_frame.png"), bytes(out / "1" / "last_frame.png")) << "the same picture from the cached atlases";
    fs::remove_all(out);
}

TEST(Tool, RenderWritesAPngAndRefusesToOverwrite) {
    const fs::path out = temp_dir("render");
    const std::string png = (out / "f.png").string();
    const RunResult r = run("render " + kScenes + "crowd_1k.json --frame 3 --characters 100 --out " + png);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_GT(fs::file_size(png), 1000u);
    const RunResult again = run("render " + kScenes + "crowd_1k.json --frame 1 --characters 100 --out " + png);
    EXPECT_NE(again.code, 0);
    fs::remove_all(out);
}

TEST(Tool, ValidateReportsBadScenesAndPassesGoodOnes) {
    const RunResult good = run("validate " + kScenes + "closeup.json");
    EXPECT_EQ(good.code, 0) << good.output;
    const fs::path out = temp_dir("validate");
    {
        std::ofstream f(out / "bad.json");
        f << R"({"camera": {"position": [0, 1, 5], "target": [0, 1, 0]}, "crowds": [{"count": 1e9}]})";
    }
    const RunResult bad = run("validate " + (out / "bad.json").string());
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.output.find("bad.json"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("/crowds/0/count"), std::string::npos) << bad.output;
    const RunResult usage = run("profile --frames x");
    EXPECT_EQ(usage.code, 2);
    fs::remove_all(out);
}

// Requests World would refuse when it queues them (a clip or an effector joint the character's type does
// not have) fail `aloha validate` too: one line per distinct problem, at the JSON pointer of the first request
// with it and with how many requests share it; crowd members' at the crowd's key; an unknown clip's line lists
// the type's clips.
TEST(Tool, ValidateChecksRequestsAgainstTheirCharacterType) {
    const fs::path out = temp_dir("validate_requests");
    aloha::test::write_text((out / "scene.json").string(), R"({"camera": {"position": [0, 1.5, 4], "target": [0, 1, 0]},
        "characters": [
          {"type": "humanoid", "position": [0, 0, 0], "requests": [{"type": "play", "clip": "no_such_clip"}]},
          {"type": "humanoid", "position": [2, 0, 0], "requests": [{"type": "reach", "effector": "Tail", "target": [2, 1, 1]}]},
          {"type": "humanoid", "position": [4, 0, 0], "requests": [{"type": "reach", "effector": "Tail", "target": [4, 1, 1]}]},
          {"type": "humanoid", "position": [6, 0, 0], "requests": [{"type": "play", "clip": "wave"}]}],
        "crowds": [{"type": "humanoid", "count": 20, "clip": "nope", "mix": {"walk": 0, "idle": 1, "reach": 0}}]})");
    const RunResult r = run("validate " + (out / "scene.json").string());
    EXPECT_EQ(r.code, 1) << r.output;
    for (const char* line : {"scene.json: /characters/0/requests/0: unknown clip 'no_such_clip' for type 'humanoid' (its clips: 'humanoid.walk_0.50', ",
                             "scene.json: /characters/1/requests/0: unknown effector joint 'Tail' for type 'humanoid' (and 1 more request like it)\n",
                             "scene.json: /characters/3/requests/0: unknown clip 'wave' for type 'humanoid' (clips are named after their type: did you "
                             "mean 'humanoid.wave'?)\n",
                             "scene.json: /crowds/0/clip: unknown clip 'nope' for type 'humanoid' (its clips: 'humanoid.walk_0.50', ",
                             "'humanoid.idle', ", "'humanoid.wave') (and 19 more requests like it)\n", "scene.json: 4 problem(s)"})
        EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
    // The same scene fails to render with the first of them.
    const RunResult render = run("render " + (out / "scene.json").string() + " --frame 0 --out " + (out / "f.png").string());
    EXPECT_EQ(render.code, 1) << render.output;
    EXPECT_NE(render.output.find("/characters/0/requests/0: unknown clip 'no_such_clip' for type 'humanoid'"), std::string::npos) << render.output;
    fs::remove_all(out);
}

TEST(Tool, ValidatePrintsTheHumanoidMapping) {
    const fs::path out = temp_dir("validate_map");
    const auto names = aloha::test::poser_names();
    aloha::test::RigStyle cm;
    cm.units_per_metre = 100.0f;
    const aloha::RawSkeleton raw =
        aloha::test::styled(aloha::test::renamed_humanoid(names, {{"lIndex1", "lHand", {0, -0.09f, 0.02f}}}), cm);
    aloha::test::write_text((out / "poser.bvh").string(), aloha::test::bvh_text(raw, 20, glm::vec3(0, 0, 1), 4.0f));
    aloha::test::write_text((out / "scene.json").string(), R"({"camera": {"position": [0, 1.5, 4], "target": [0, 1, 0]},
        "character_types": [{"name": "poser", "bvh": "poser.bvh"}],
        "characters": [{"type": "poser", "position": [0, 0, 0]}]})");
    const RunResult r = run("validate " + (out / "scene.json").string());
    EXPECT_EQ(r.code, 0) << r.output;
    std::printf("%s", r.output.c_str());  // the report docs/CHARACTERS.md shows
    for (const char* line : {"character type 'poser'", "  convention Poser / DAZ: humanoid",
                             "  mapping (canonical <- file, 21 of 31): Hips <- hip, LeftHip <- lThigh, RightHip <- rThigh",
                             "  joints ignored by the layers (1): lIndex1",
                             "  units: centimetres; file axes: up +Y, forward +Z; standing height 1.68 m",
                             "  clip playback: yes (13 clips: poser.mocap 0.63 s (root motion: 0.76 m), poser.inplace 0.63 s, poser.walk_0.50 ",
                             "poser.idle 8.00 s, poser.turn 4.00 s (root motion: 360 deg)",
                             "  kinematic and dynamic walk: yes", "  geometric levels layered and subdivided: yes",
                             "  note: generated motion retargeted from the built-in humanoid at 1.75 m (pelvis travel x1.000): 8 gaits, idle, "
                             "turn, wave; the gaits are its walk"})
        EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
    fs::remove_all(out);
}

// `aloha validate` on a character file alone (no scene): the same report a scene's type gets, the humanoid
// found through a VRM declaration or a naming convention; a broken file fails naming it.
TEST(Tool, ValidateACharacterFileAlone) {
    const fs::path out = temp_dir("validate_file");
    const auto numbered = aloha::test::numbered_names();
    const aloha::RawSkeleton raw = aloha::test::renamed_humanoid(numbered);
    nlohmann::json j = nlohmann::json::parse(aloha::test::gltf_text(raw, 1, 0.3f));
    aloha::test::add_vrm_humanoid(j, raw, numbered, true);
    aloha::test::write_text((out / "avatar.vrm").string(), j.dump());
    const RunResult vrm = run("validate " + (out / "avatar.vrm").string());
    EXPECT_EQ(vrm.code, 0) << vrm.output;
    for (const char* line : {"character type 'avatar'", "  convention VRM 1.0 humanoid: humanoid", "LeftKnee <- Bone.", " (file)",
                             "avatar.vrm: ok (a character file"})
        EXPECT_NE(vrm.output.find(line), std::string::npos) << line << "\n" << vrm.output;
    aloha::test::RigStyle cm;
    cm.units_per_metre = 100.0f;
    const aloha::RawSkeleton poser = aloha::test::styled(aloha::test::renamed_humanoid(aloha::test::poser_names()), cm);
    aloha::test::write_text((out / "walk.BVH").string(), aloha::test::bvh_text(poser, 20, glm::vec3(0, 0, 1), 4.0f));
    const RunResult bvh = run("validate " + (out / "walk.BVH").string());
    EXPECT_EQ(bvh.code, 0) << bvh.output;
    EXPECT_NE(bvh.output.find("  convention Poser / DAZ: humanoid"), std::string::npos) << bvh.output;
    EXPECT_NE(bvh.output.find("  units: centimetres"), std::string::npos) << bvh.output;
    aloha::test::write_text((out / "broken.glb").string(), "glTF but not really");
    const RunResult broken = run("validate " + (out / "broken.glb").string());
    EXPECT_EQ(broken.code, 1) << broken.output;
    EXPECT_NE(broken.output.find("broken.glb: "), std::string::npos) << broken.output;
    EXPECT_NE(broken.output.find("broken.glb: 1 problem(s)"), std::string::npos) << broken.output;
    fs::remove_all(out);
}

// One file per naming convention, written as that convention's tools write them (units, up and
// facing axes, rest frames), and a quadruped: `aloha validate` prints for each the convention and
// mapping it found, the units and axes it assumed and the levels it can use.
TEST(Tool, ValidatePrintsEveryConvention) {
    namespace t = aloha::test;
    const fs::path out = temp_dir("validate_conventions");
    struct Case {
        const char* name;
        std::map<std::string, std::string> names;
        const char* format;       // "bvh" or "gltf"
        float units_per_metre;
        glm::quat axes;           // file model = axes * canonical model
        bool t_pose, bone_frames;
        const char* convention;   // expected report line
        const char* units;        // expected units line prefix
    };
    std::map<std::string, std::string> cmu;
    for (const aloha::CanonicalJoint& c : aloha::canonical_humanoid()) cmu[c.name] = c.name;
    const glm::quat id(1, 0, 0, 0);
    const glm::quat z_up = glm::angleAxis(1.5707963f, glm::vec3(1, 0, 0));                       // +Y -> +Z, +Z -> -Y
    const glm::quat z_up_x_fwd = glm::angleAxis(2.0943951f, glm::normalize(glm::vec3(1, 1, 1)));  // +Y -> +Z, +Z -> +X
    const glm::quat minus_z = glm::angleAxis(3.1415927f, glm::vec3(0, 1, 0));                     // +Z -> -Z
    const std::vector<Case> cases = {
        {"cmu", cmu, "bvh", 1.0f / 0.056444f, id, false, false, "convention CMU BVH: humanoid", "units: CMU units"},
        {"mixamo", t::mixamo_names(), "gltf", 100.0f, id, true, true, "convention Mixamo / HumanIK: humanoid", "units: centimetres; file axes: up +Y, forward +Z"},
        {"rigify", t::rigify_names("DEF-"), "gltf", 1.0f, z_up, true, true, "convention Blender Rigify: humanoid", "units: metres; file axes: up +Z, forward -Y"},
        {"blender", t::unity_names(".L", ".R", false), "gltf", 1.0f, z_up, false, true, "convention Unity Humanoid / VRM: humanoid", "units: metres; file axes: up +Z, forward -Y"},
        {"unreal", t::unreal_names(), "gltf", 100.0f, z_up_x_fwd, false, true, "convention Unreal mannequin: humanoid", "units: centimetres; file axes: up +Z, forward +X"},
        {"poser", t::poser_names(), "bvh", 100.0f, id, false, false, "convention Poser / DAZ: humanoid", "units: centimetres; file axes: up +Y, forward +Z"},
        {"daz", t::daz_names(), "bvh", 100.0f, id, false, false, "convention Poser / DAZ: humanoid", "units: centimetres; file axes: up +Y, forward +Z"},
        {"unity", t::unity_humanoid_names(), "gltf", 1.0f, id, false, true, "convention Unity Humanoid / VRM: humanoid", "units: metres; file axes: up +Y, forward +Z"},
        {"vrm", t::vrm_names(), "gltf", 1.0f, minus_z, false, false, "convention Unity Humanoid / VRM: humanoid", "units: metres; file axes: up +Y, forward -Z"},
        {"vroid", t::vroid_names(), "gltf", 1.0f, minus_z, false, false, "convention VRoid: humanoid", "units: metres; file axes: up +Y, forward -Z"},
    };
    std::string types, characters;
    float x = 0.0f;
    for (const Case& c : cases) {
        t::RigStyle style;
        style.units_per_metre = c.units_per_metre;
        style.axes = c.axes;
        style.bone_frames = c.bone_frames;
        const aloha::RawSkeleton raw = t::styled(t::renamed_humanoid(c.names, {}, c.t_pose), style);
        const std::string file = std::string(c.name) + "." + c.format;
        if (std::string(c.format) == "bvh")
            t::write_text((out / file).string(), t::bvh_text(raw, 20, c.axes * glm::vec3(0, 0, 1), 4.0f));
        else
            t::write_text((out / file).string(), t::gltf_text(raw, 1, 0.3f));
        types += std::string(types.empty() ? "" : ", ") + R"({"name": ")" + c.name + R"(", ")" + c.format + R"(": ")" + file + "\"}";
        characters += std::string(characters.empty() ? "" : ", ") + R"({"type": ")" + c.name + R"(", "position": [)" +
                      std::to_string(x) + ", 0, 0]}";
        x += 1.0f;
    }
    // A quadruped in centimetres (no convention, no humanoid).
    t::write_text((out / "dog.bvh").string(), t::bvh_text(t::quadruped(), 20, glm::vec3(0, 0, 1), 3.0f));
    types += R"(, {"name": "dog", "bvh": "dog.bvh"})";
    characters += R"(, {"type": "dog", "position": [-2, 0, 0]})";
    t::write_text((out / "scene.json").string(), R"({"camera": {"position": [4, 1.5, 8], "target": [4, 1, 0]}, "character_types": [)" +
                                                     types + R"(], "characters": [)" + characters + "]}");
    const RunResult r = run("validate " + (out / "scene.json").string());
    EXPECT_EQ(r.code, 0) << r.output;
    std::printf("%s", r.output.c_str());  // the reports docs/CHARACTERS.md quotes
    // Each type's block: from its header line to the next one.
    auto block = [&](const std::string& name) {
        const size_t at = r.output.find("character type '" + name + "'");
        if (at == std::string::npos) return std::string();
        return r.output.substr(at, r.output.find("character type '", at + 1) - at);
    };
    for (const Case& c : cases) {
        const std::string b = block(c.name);
        ASSERT_FALSE(b.empty()) << c.name << "\n" << r.output;
        for (const std::string& line : {std::string("  ") + c.convention, std::string("  ") + c.units, std::string("  kinematic and dynamic walk: yes"),
                                       std::string("  reach: yes"), std::string("  geometric levels layered and subdivided: yes")})
            EXPECT_NE(b.find(line), std::string::npos) << c.name << ": " << line << "\n" << b;
        // Every required canonical joint mapped, nothing of the fixture ignored.
        EXPECT_NE(b.find("  joints ignored by the layers (0): none"), std::string::npos) << b;
    }
    const std::string d = block("dog");
    for (const char* line : {": not a humanoid (missing LeftHip, RightHip, LeftKnee", "  kinematic and dynamic walk: no",
                             "  geometric level rigid proxy: yes", "  geometric levels layered and subdivided: refused (no muscles; drawn as rigid proxies)"})
        EXPECT_NE(d.find(line), std::string::npos) << line << "\n" << d;
    fs::remove_all(out);
}

}  // namespace

namespace {

// Reads a CSV written by `aloha export` (no quoted fields in the built-in scenes) into rows of fields.
std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::vector<std::string>> rows;
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        std::stringstream ss(line);
        std::string f;
        while (std::getline(ss, f, ',')) fields.push_back(f);
        rows.push_back(std::move(fields));
    }
    return rows;
}

}  // namespace

// Export: every joint of the chosen characters on the chosen frames, with level and method; the same
// positions as a second run (deterministic); refuses to overwrite; bad selections are named.
TEST(Tool, ExportWritesJointsOfTheChosenCharactersAndFrames) {
    const fs::path out = temp_dir("export");
    const std::string csv = (out / "joints.csv").string();
    const RunResult r = run("export " + kScenes + "crowd_1k.json --joints " + csv + " --characters 3,10-11 --frames 4:7");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto rows = read_csv(csv);
    ASSERT_GT(rows.size(), 1u);
    const std::vector<std::string> header = {"frame", "time_s", "character", "type", "id", "anim_level", "level_index",
                                             "update_interval", "method", "in_transition", "joint", "joint_name", "x", "y", "z"};
    EXPECT_EQ(rows[0], header);
    std::set<std::string> characters, frames;
    size_t per_character_frame = 0;
    for (size_t i = 1; i < rows.size(); ++i) {
        ASSERT_EQ(rows[i].size(), header.size()) << "row " << i;
        characters.insert(rows[i][2]);
        frames.insert(rows[i][0]);
        if (rows[i][2] == "3" && rows[i][0] == "4") ++per_character_frame;
        EXPECT_TRUE(rows[i][8] == "clip" || rows[i][8] == "kinematic" || rows[i][8] == "dynamic" ||
                    rows[i][8] == "play_clip" || rows[i][8] == "rest") << rows[i][8];
    }
    EXPECT_EQ(characters, (std::set<std::string>{"3", "10", "11"}));
    EXPECT_EQ(frames, (std::set<std::string>{"4", "5", "6"}));
    EXPECT_EQ(rows.size() - 1, 3 * 3 * per_character_frame);  // every joint of each character on each frame
    const RunResult again = run("export " + kScenes + "crowd_1k.json --joints " + csv + " --characters 3,10-11 --frames 4:7");
    EXPECT_NE(again.code, 0);
    EXPECT_NE(again.output.find("already exists"), std::string::npos) << again.output;
    const std::string csv2 = (out / "joints2.csv").string();
    ASSERT_EQ(run("export " + kScenes + "crowd_1k.json --joints " + csv2 + " --characters 3,10-11 --frames 4:7").code, 0);
    EXPECT_EQ(read_csv(csv2), rows);
    const RunResult past = run("export " + kScenes + "crowd_1k.json --joints " + (out / "x.csv").string() + " --characters 5000");
    EXPECT_EQ(past.code, 2);
    EXPECT_NE(past.output.find("character 5000"), std::string::npos) << past.output;
    EXPECT_FALSE(fs::exists(out / "x.csv"));
}

// --motion-metrics: report.json carries per-level figures and the bars; the table is printed.
TEST(Tool, ProfileMotionMetricsReportsSkateAndPopsPerLevel) {
    const fs::path out = temp_dir("motion_metrics");
    const RunResult r = run("profile " + kScenes + "crowd_1k.json --no-render --motion-metrics --frames 60 --warmup 2 "
                            "--characters 100 --quiet --out " + (out / "p").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("motion metrics"), std::string::npos) << r.output;
    std::ifstream in(out / "p" / "report.json");
    const nlohmann::json m = nlohmann::json::parse(in)["motion_metrics"];
    ASSERT_TRUE(m.is_object());
    EXPECT_EQ(m["skate_bar_mm_per_m"], 10.0);
    EXPECT_NEAR(m["contact"]["height_m"].get<double>(), 0.005, 1e-9);  // a float in the report
    ASSERT_FALSE(m["per_level_and_interval"].empty());
    double walked = 0.0;
    for (const auto& b : m["per_level_and_interval"]) {
        for (const char* k : {"anim_level", "update_interval", "walked_m", "skate_mm_per_m", "switch_frames",
                              "worst_switch_cm", "ordinary_p95_cm", "transition_frames", "worst_transition_cm"})
            EXPECT_TRUE(b.contains(k)) << k;
        walked += b["walked_m"].get<double>();
    }
    EXPECT_NEAR(m["overall"]["walked_m"].get<double>(), walked, 1e-6 * walked);
    EXPECT_GT(walked, 0.0);  // the crowd walks
}

// The budget parts in the report: each active part's time against its target over every frame and
// from where it settled, level changes per second over both; the single total as its own mode.
TEST(Tool, ProfileReportsBudgetPartsSettledAndLevelChanges) {
    const fs::path out = temp_dir("budget_parts");
    auto report_of = [&](const std::string& extra, const std::string& name) {
        const RunResult r = run("profile " + kScenes + "plaza_budget.json --no-render --frames 40 --warmup 2 --characters 60 "
                                "--quiet " + extra + " --out " + (out / name).string());
        EXPECT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("level changes per second"), std::string::npos) << r.output;
        std::ifstream in(out / name / "report.json");
        return std::make_pair(nlohmann::json::parse(in), r.output);
    };
    // Targets of 1 µs: out of reach (every character demoted as far as it goes still costs more), so
    // neither part ever settles and the report says so.
    const auto [parts, printed] = report_of("--budget-animation-ms 0.001 --budget-geometry-ms 0.001", "parts");
    EXPECT_EQ(parts["budget"]["mode"], "parts");
    for (const char* part : {"animation", "geometry"}) {
        const nlohmann::json& p = parts["budget"][part];
        EXPECT_TRUE(p["active"].get<bool>()) << part;
        EXPECT_NEAR(p["target_ms"].get<double>(), 0.001, 1e-9) << part;  // a float in the report
        ASSERT_TRUE(p.contains("settled")) << part;
        EXPECT_TRUE(p["settled"].is_null()) << part;
    }
    EXPECT_TRUE(parts["level_changes_per_second_settled"].is_null());
    EXPECT_NE(printed.find("never settled"), std::string::npos) << printed;  // 1 µs is out of reach
    const auto [single, single_printed] = report_of("--budget-single-ms 1000", "single");
    EXPECT_EQ(single["budget"]["mode"], "total");
    EXPECT_FALSE(single["budget"]["animation"]["active"].get<bool>());
    // 1 s is far over what 60 characters cost: settled at the first measured frame.
    EXPECT_EQ(single["budget"]["settled_from_frame"], 0);
    EXPECT_NEAR(single["level_changes_per_second_settled"]["seconds"].get<double>(), 40 * 0.0166667, 1e-4);  // scene dt
    fs::remove_all(out);
}
