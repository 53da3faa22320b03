// `aloha export SCENE --frame N --character I [--level L] --out FILE.glb`: runs the built tool on a small
// fixture scene, reads the .glb back with tinygltf and compares it with an in-process World run to the
// same frame (the tool's run is deterministic: same scene, same inputs, same state).
#include "host/scene/character_runtime.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"
#include "systems/frame/placement.hpp"
#include "tests/host/tool/tool_run.hpp"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace aloha;

using test::RunResult;

RunResult run_tool(const std::string& args) { return test::run(args); }

// Three humanoids close to the camera for 6 frames at 30 Hz: character 0 walks, 1 and 2 stand.
const char* kScene = R"({
  "name": "export_fixture", "rules": "builtin:default", "frames": 6, "dt": 0.0333333,
  "viewport": {"width": 320, "height": 240},
  "camera": {"position": [0.0, 1.2, 4.0], "target": [0.0, 1.0, 0.0], "fov_deg": 45},
  "characters": [
    {"type": "humanoid", "position": [0, 0, 0], "importance": 1.0,
     "requests": [{"type": "walk", "speed": 1.2, "direction": [1, 0, 0], "duration": 5.0}]},
    {"type": "humanoid", "position": [1.0, 0, 0], "heading_deg": 90},
    {"type": "humanoid", "position": [-1.0, 0, 0]}
  ]
})";

class ExportSkin : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("aloha_export_skin_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        scene = (dir / "scene.json").string();
        std::ofstream(scene) << kScene;
    }
    void TearDown() override { fs::remove_all(dir); }

    // The tool's command line for `args`: budget off and the tier named, so that levels depend on neither
    // timings nor the GPU found ("auto").
    RunResult export_skin(const std::string& args) {
        return run_tool("export " + scene + " --budget off --tier high --threads 1 " + args);
    }

    // The World as the tool runs it, stepped to `frame` with `character` held at `level` (if any).
    std::unique_ptr<World> world_at(uint32_t frame, uint32_t character, std::optional<uint8_t> level) {
        auto desc = load_scene(scene);
        EXPECT_TRUE(desc.ok()) << (desc.ok() ? "" : desc.error().to_string());
        if (!desc.ok()) return nullptr;
        WorldOptions o;
        o.threads = 1;
        o.budget = false;
        o.tier = "high";
        o.pose_every_character = true;
        o.keep_refined_surfaces = true;
        auto w = World::create(desc.value(), o);
        EXPECT_TRUE(w.ok()) << (w.ok() ? "" : w.error().to_string());
        if (!w.ok()) return nullptr;
        if (level) {
            EXPECT_TRUE(w.value()->pin_geom_level(character, *level).ok());
        }
        for (uint32_t f = 0; f <= frame; ++f) w.value()->step();
        return std::move(w.value());
    }

    fs::path dir;
    std::string scene;
};

tinygltf::Model read_glb(const std::string& path) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path)) << err;
    EXPECT_TRUE(err.empty()) << err;
    return model;
}

// The floats of a tightly packed VEC3 float accessor.
std::vector<glm::vec3> vec3s(const tinygltf::Model& m, int accessor) {
    const tinygltf::Accessor& a = m.accessors.at(static_cast<size_t>(accessor));
    const tinygltf::BufferView& v = m.bufferViews.at(static_cast<size_t>(a.bufferView));
    EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(a.type, TINYGLTF_TYPE_VEC3);
    EXPECT_GE(v.byteLength, a.count * sizeof(glm::vec3));
    std::vector<glm::vec3> out(a.count);
    std::memcpy(out.data(), m.buffers.at(static_cast<size_t>(v.buffer)).data.data() + v.byteOffset + a.byteOffset,
                a.count * sizeof(glm::vec3));
    return out;
}

// Checks `path` is a well-formed glTF 2.0 skin of character `character` of `world` and returns its positions.
std::vector<glm::vec3> check_document(const std::string& path, World& world, uint32_t character) {
    const tinygltf::Model m = read_glb(path);
    EXPECT_EQ(m.asset.version, "2.0");
    EXPECT_EQ(m.meshes.size(), 1u);
    if (m.meshes.size() != 1 || m.meshes[0].primitives.size() != 1) return {};
    const tinygltf::Primitive& prim = m.meshes[0].primitives[0];
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
    const tinygltf::Accessor& pos = m.accessors.at(static_cast<size_t>(prim.attributes.at("POSITION")));
    const tinygltf::Accessor& nrm = m.accessors.at(static_cast<size_t>(prim.attributes.at("NORMAL")));
    const tinygltf::Accessor& idx = m.accessors.at(static_cast<size_t>(prim.indices));
    EXPECT_EQ(pos.minValues.size(), 3u);  // glTF 2.0 requires POSITION's bounds
    EXPECT_EQ(pos.maxValues.size(), 3u);
    EXPECT_EQ(nrm.count, pos.count);
    EXPECT_EQ(idx.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    EXPECT_EQ(idx.count % 3, 0u);
    const std::vector<glm::vec3> positions = vec3s(m, prim.attributes.at("POSITION"));
    for (const glm::vec3& p : positions)
        for (int k = 0; k < 3 && pos.minValues.size() == 3 && pos.maxValues.size() == 3; ++k) {
            EXPECT_GE(p[k], pos.minValues[static_cast<size_t>(k)]);
            EXPECT_LE(p[k], pos.maxValues[static_cast<size_t>(k)]);
        }
    for (const glm::vec3& n : vec3s(m, prim.attributes.at("NORMAL"))) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
    const tinygltf::BufferView& iv = m.bufferViews.at(static_cast<size_t>(idx.bufferView));
    const auto* indices = reinterpret_cast<const uint32_t*>(m.buffers[0].data.data() + iv.byteOffset + idx.byteOffset);
    for (size_t i = 0; i < idx.count; ++i) EXPECT_LT(indices[i], pos.count);
    // The skeleton: the placement node, then one node per joint of the rig, named and parented as in it.
    MotionSample sample;
    world.motion_sample(character, sample);
    const Skeleton& skeleton = world.type(sample.type).skeleton;
    EXPECT_EQ(m.nodes.size(), 2u + static_cast<size_t>(skeleton.joint_count()));
    for (int j = 0; j < skeleton.joint_count() && m.nodes.size() == 2u + static_cast<size_t>(skeleton.joint_count()); ++j) {
        EXPECT_EQ(m.nodes[static_cast<size_t>(j) + 2].name, skeleton.names()[static_cast<size_t>(j)]);
        const int parent = skeleton.parents()[static_cast<size_t>(j)] < 0 ? 1 : skeleton.parents()[static_cast<size_t>(j)] + 2;
        const auto& kids = m.nodes[static_cast<size_t>(parent)].children;
        EXPECT_NE(std::find(kids.begin(), kids.end(), j + 2), kids.end()) << "joint " << j;
    }
    return positions;
}

// The World's displayed skin of `character` in world space (its controller's surface, placed).
std::vector<glm::vec3> world_skin(World& world, uint32_t character) {
    MotionSample sample;
    world.motion_sample(character, sample);
    const CharacterRuntime& rt = world.runtime(sample.type);
    const glm::mat4 placed = world_matrix(character_group(world.registry()).span<Transform>()[rt.element_of_character[sample.id]]);
    std::vector<glm::vec3> out;
    for (const glm::vec3& p : rt.geometry->surface(sample.id).positions) out.push_back(glm::vec3(placed * glm::vec4(p, 1.0f)));
    return out;
}

void expect_same_points(const std::vector<glm::vec3>& file, const std::vector<glm::vec3>& world) {
    ASSERT_EQ(file.size(), world.size());
    ASSERT_FALSE(file.empty());
    float worst = 0.0f;
    for (size_t i = 0; i < file.size(); ++i) worst = std::max(worst, glm::length(file[i] - world[i]));
    EXPECT_LT(worst, 1e-5f);  // the same floats, written and read back: equal but for float rounding
}

TEST_F(ExportSkin, WritesTheDisplayedSkinAtTheForcedLevel) {
    const std::string out = (dir / "walker.glb").string();
    const RunResult r = export_skin("--frame 4 --character 0 --level 1 --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_FALSE(fs::exists(out + ".partial"));
    auto world = world_at(4, 0, uint8_t{1});
    ASSERT_TRUE(world);
    MotionSample sample;
    world->motion_sample(0, sample);
    EXPECT_EQ(world->runtime(sample.type).geometry->level_of(sample.id), 1);
    expect_same_points(check_document(out, *world, 0), world_skin(*world, 0));
}

TEST_F(ExportSkin, WritesTheCurrentLevelWithoutLevel) {
    const std::string out = (dir / "stander.glb").string();
    const RunResult r = export_skin("--frame 5 --character 2 --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    auto world = world_at(5, 2, std::nullopt);
    ASSERT_TRUE(world);
    expect_same_points(check_document(out, *world, 2), world_skin(*world, 2));
}

TEST_F(ExportSkin, RigidProxyLevelWritesTheBoxesItDraws) {
    const std::string out = (dir / "proxy.glb").string();
    const RunResult r = export_skin("--frame 2 --character 1 --level 6 --out " + out);  // proxy
    ASSERT_EQ(r.code, 0) << r.output;
    auto world = world_at(2, 1, uint8_t{6});
    ASSERT_TRUE(world);
    MotionSample sample;
    world->motion_sample(1, sample);
    const size_t boxes = world->runtime(sample.type).proxy_joints.size();
    const std::vector<glm::vec3> positions = check_document(out, *world, 1);
    EXPECT_EQ(positions.size(), boxes * 24);  // 6 faces x 4 corners per box
}

TEST_F(ExportSkin, RefusesBadArgumentsNamingThemAndTheRange) {
    const std::string out = (dir / "bad.glb").string();
    struct Case {
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {"--frame 2 --character 3 --out " + out, "--character 3 is past the crowd"},
        {"--frame 6 --character 0 --out " + out, "--frame 6 is past the scene"},
        {"--frame 2 --character 0 --level 9 --out " + out, "--level 9 is past the rule table's geometric levels"},
        {"--frame 2 --character 0 --level 7 --out " + out, "is an impostor"},
        {"--frame 2 --character 0 --level 8 --out " + out, "is hidden"},
        {"--character 0 --out " + out, "needs --frame"},
        {"--frame 1 --out " + out, "needs --character"},
        {"--frame 1 --character 0 --out " + (dir / "bad.obj").string(), "expects a .glb file"},
        {"--frame 1 --character 0 --frames 2 --out " + out, "--frames go with --joints"},
    };
    for (const Case& c : cases) {
        const RunResult r = export_skin(c.args);
        EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
    // The ranges are named: 3 characters (0 to 2), 6 frames (0 to 5), 9 levels (0 to 8).
    EXPECT_NE(export_skin("--frame 2 --character 3 --out " + out).output.find("0 to 2"), std::string::npos);
    EXPECT_NE(export_skin("--frame 6 --character 0 --out " + out).output.find("0 to 5"), std::string::npos);
    EXPECT_NE(export_skin("--frame 1 --character 0 --level 9 --out " + out).output.find("0 to 8"), std::string::npos);
}

TEST_F(ExportSkin, NeverOverwritesWithoutForce) {
    const std::string out = (dir / "kept.glb").string();
    std::ofstream(out) << "mine";
    const RunResult r = export_skin("--frame 1 --character 1 --out " + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("already exists"), std::string::npos) << r.output;
    std::ifstream in(out);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "mine");
    ASSERT_EQ(export_skin("--frame 1 --character 1 --force --out " + out).code, 0);
    EXPECT_GT(fs::file_size(out), 1000u);
}

}  // namespace
