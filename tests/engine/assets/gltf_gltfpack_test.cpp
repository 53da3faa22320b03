// Characters re-packed by gltfpack (meshoptimizer's glTF optimiser, Debian package gltfpack): quantised
// (its default: KHR_mesh_quantization, KHR_texture_transform), compressed (-c, -cc: EXT_meshopt_compression
// with filters) and plain (-noq). gltfpack re-orders vertices, resamples animations at 30 Hz and rewrites
// the node tree, so what the loader returns is compared with the original as sets: every vertex of each
// has one of the other within gltfpack's quantisation step, the same triangles count, and the clip's pose at
// its original keys. The tests skip, saying so, when gltfpack is not installed (scripts/setup.sh installs it).
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/skinned_cylinder.hpp"
#include "tests/common/test_assets.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#ifndef ALOHA_GLTFPACK
#error "ALOHA_GLTFPACK must be defined (tests/engine/assets/CMakeLists.txt: gltfpack's path, or empty)"
#endif

namespace aloha {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct Packed {
    fs::path dir;
    Packed() : dir(fs::temp_directory_path() / ("aloha_gltfpack_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Packed() { fs::remove_all(dir); }
    // Runs gltfpack on `in` with `flags`; returns the output path (or "" with a failure recorded).
    std::string pack(const std::string& in, const std::string& flags, const std::string& name) const {
        const std::string out = (dir / name).string();
        const std::string cmd = std::string("'") + ALOHA_GLTFPACK + "' -i '" + in + "' -o '" + out + "' " + flags + " > '" + (dir / "log.txt").string() + "' 2>&1";
        if (std::system(cmd.c_str()) != 0) {
            std::ifstream log(dir / "log.txt");
            ADD_FAILURE() << cmd << " failed:\n" << std::string(std::istreambuf_iterator<char>(log), {});
            return {};
        }
        return out;
    }
};

// Largest distance from a vertex of `a` to the nearest vertex of `b` whose normal is within 0.1 of it.
float one_way(const GltfSkinnedMesh& a, const GltfSkinnedMesh& b) {
    float worst = 0.0f;
    for (size_t i = 0; i < a.positions.size(); ++i) {
        float best = 1e30f;
        for (size_t k = 0; k < b.positions.size(); ++k)
            if (glm::length(a.normals[i] - b.normals[k]) < 0.1f) best = std::min(best, glm::length(a.positions[i] - b.positions[k]));
        worst = std::max(worst, best);
    }
    return worst;
}

// The rotation of runtime track `t` at time `s` (linear keys, normalised linear interpolation).
glm::quat sample(const RawTrack<glm::quat>& t, float s) {
    size_t k = 0;
    while (k + 1 < t.times.size() && t.times[k + 1] <= s) ++k;
    if (k + 1 >= t.times.size()) return t.values.back();
    const float f = (s - t.times[k]) / (t.times[k + 1] - t.times[k]);
    glm::quat b = t.values[k + 1];
    if (glm::dot(t.values[k], b) < 0.0f) b = -b;
    return glm::normalize(t.values[k] * (1.0f - f) + b * f);
}

TEST(GltfGltfpack, RepackedCylinderLoadsAsTheOriginal) {
    if (std::string(ALOHA_GLTFPACK).empty()) GTEST_SKIP() << "gltfpack was not found when the build was configured (install it: scripts/setup.sh)";
    const test::SkinnedCylinder c;
    test::GltfBuilder b = test::plain_cylinder(c);
    // A clip turning the tip 0, 30, 60 degrees about z at 0, 0.5 and 1 s (keys on gltfpack's 30 Hz frames).
    const std::vector<float> times{0.0f, 0.5f, 1.0f};
    const std::vector<glm::vec4> rotations{{0, 0, 0, 1}, {0, 0, 0.25881905f, 0.96592583f}, {0, 0, 0.5f, 0.8660254f}};
    b.doc["animations"] = json::array({{{"name", "bend"},
                                        {"samplers", json::array({{{"input", b.scalars(times)}, {"output", b.vec4(rotations)}}})},
                                        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}})}}});
    Packed packed;
    const std::string in = (packed.dir / "cylinder.gltf").string();
    std::ofstream(in) << b.dump();
    Result<GltfCharacter> want = load_gltf_character(in);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    // gltfpack's default steps: 14-bit positions over the 2 m extent, 8-bit normals, 12-bit texture coordinates.
    const float step = 2.0f / 16383.0f;
    for (const auto& [flags, name] : std::vector<std::pair<std::string, std::string>>{{"", "q.glb"}, {"-c", "c.glb"}, {"-cc", "cc.glb"}, {"-noq", "noq.glb"}}) {
        SCOPED_TRACE("gltfpack " + flags);
        const std::string out = packed.pack(in, flags, name);
        ASSERT_FALSE(out.empty());
        Result<GltfCharacter> got = load_gltf_character(out);
        ASSERT_TRUE(got.ok()) << got.error().to_string();
        ASSERT_EQ(got.value().meshes.size(), 1u);
        const GltfSkinnedMesh& g = got.value().meshes[0];
        const GltfSkinnedMesh& w = want.value().meshes[0];
        EXPECT_EQ(g.indices.size(), w.indices.size());
        // Each position within one quantisation step (gltfpack rounds to its grid: half a step per axis, so
        // under sqrt(3)/2 of a step; one step leaves room for float rounding of the dequantisation).
        EXPECT_LE(one_way(w, g), step);
        EXPECT_LE(one_way(g, w), step);
        // Texture coordinates span [0, 1] x [0.1, 0.9]: the gltfpack grid is 1/4095 of the extent (at most 1), so the
        // ends are half a step off at most, plus float rounding.
        float uv_lo = 1e30f, uv_hi = -1e30f;
        for (const glm::vec2& uv : g.uvs) uv_lo = std::min(uv_lo, uv.y), uv_hi = std::max(uv_hi, uv.y);
        EXPECT_NEAR(uv_lo, 0.1f, 0.5f / 4095.0f + 1e-6f);
        EXPECT_NEAR(uv_hi, 0.9f, 0.5f / 4095.0f + 1e-6f);
        ASSERT_EQ(got.value().clips.size(), 1u);
        const RawAnimation& clip = got.value().clips[0];
        EXPECT_NEAR(clip.duration, 1.0f, 1e-4f);
        size_t animated = 0;
        for (const RawJointTracks& t : clip.tracks) {
            if (t.rotations.times.size() < 2) continue;
            ++animated;
            for (size_t k = 0; k < times.size(); ++k) {
                const glm::quat q = sample(t.rotations, times[k]);
                const float dot = std::abs(q.x * rotations[k].x + q.y * rotations[k].y + q.z * rotations[k].z + q.w * rotations[k].w);
                // gltfpack's 12-bit rotation components (its -ar default): each within 0.5/2047, so the quaternion moves
                // by |dq| < 4.9e-4 and its half-angle by as much; the keys sit on its 30 Hz frames, so resampling adds
                // nothing. cos(1e-3) leaves a factor of 2 for the renormalisation.
                EXPECT_GT(dot, std::cos(1e-3f)) << "key " << k;
            }
        }
        EXPECT_EQ(animated, 1u);
    }
}

// The shared CesiumMan (not in the repository) re-packed each way: the same triangles, and every skinned
// vertex at rest within a quantisation step of the original's (14 bits over its 1.5 m extent).
TEST(GltfGltfpack, RepackedCesiumManMatchesTheOriginal) {
    if (std::string(ALOHA_GLTFPACK).empty()) GTEST_SKIP() << "gltfpack was not found when the build was configured (install it: scripts/setup.sh)";
    const std::optional<std::string> asset = test::find_test_asset("CesiumMan.glb");
    if (!asset) GTEST_SKIP() << test::missing_test_asset_message("CesiumMan.glb");
    Result<GltfCharacter> want = load_gltf_character(*asset);
    ASSERT_TRUE(want.ok()) << want.error().to_string();
    Packed packed;
    size_t triangles = 0;
    for (const GltfSkinnedMesh& m : want.value().meshes) triangles += m.indices.size() / 3;
    for (const auto& [flags, name] : std::vector<std::pair<std::string, std::string>>{{"", "q.glb"}, {"-c", "c.glb"}}) {
        SCOPED_TRACE("gltfpack " + flags);
        const std::string out = packed.pack(*asset, flags, name);
        ASSERT_FALSE(out.empty());
        Result<GltfCharacter> got = load_gltf_character(out);
        ASSERT_TRUE(got.ok()) << got.error().to_string();
        size_t got_triangles = 0;
        for (const GltfSkinnedMesh& m : got.value().meshes) got_triangles += m.indices.size() / 3;
        EXPECT_EQ(got_triangles, triangles);
        ASSERT_EQ(got.value().meshes.size(), 1u);
        ASSERT_EQ(want.value().meshes.size(), 1u);
        const float step = 1.5065499f / 16383.0f;
        EXPECT_LE(one_way(want.value().meshes[0], got.value().meshes[0]), step);
        EXPECT_LE(one_way(got.value().meshes[0], want.value().meshes[0]), step);
        ASSERT_EQ(got.value().clips.size(), want.value().clips.size());
        EXPECT_NEAR(got.value().clips[0].duration, want.value().clips[0].duration, 1.0f / 30.0f);
    }
}

}  // namespace
}  // namespace aloha
