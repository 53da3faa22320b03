// The bake cache seen from a World: a world made from the cache (warm) has bit-identical skins and the
// same state hash as the one that baked them (cold); damaged entries are rebuilt; a cache directory
// that cannot be made leaves the world as it would be without one. Each test uses its own directory
// (the suite's shared one would make the cold path warm).
#include "engine/core/blob_store.hpp"
#include "host/scene/character_runtime.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"
#include "host/scene/world_diagnostics.hpp"
#include "tests/host/scene/world_test_util.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

namespace aloha {
namespace {

namespace fs = std::filesystem;
using scene_test::make_world;

// A scene of 6 humanoids of 1 body variant (2 generated types, the crowd's base and its variant: few
// bakes, every path of a scene crowd).
struct WorldBakeCache : ::testing::Test {
    fs::path dir;
    SceneDesc scene;
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("aloha_world_bake_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        const fs::path file = dir / "scene.json";
        std::ofstream(file) << R"({"name": "bake", "rules": "builtin:default", "frames": 20,
            "camera": {"position": [0, 2, 9], "target": [0, 1, 0], "fov_deg": 50},
            "crowds": [{"type": "humanoid", "count": 6, "layout": "grid", "spacing": 1.5, "seed": 5,
                        "mix": {"walk": 0.5, "idle": 0.5, "reach": 0.0},
                        "height": [1.6, 1.9], "build": [0.2, 0.8], "variants": 1}]})";
        auto loaded = load_scene(file.string());
        ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
        scene = loaded.value();
    }
    void TearDown() override { fs::remove_all(dir); }
    WorldOptions options(const fs::path& cache) const {
        WorldOptions o;
        o.threads = 1;
        o.bake_cache_dir = cache.string();
        return o;
    }
    // The entries in `cache` with their inode numbers (a rewrite renames a new file over the old).
    static std::map<std::string, ino_t> entries(const fs::path& cache) {
        std::map<std::string, ino_t> out;
        for (const auto& e : fs::directory_iterator(cache)) {
            struct stat st {};
            if (::stat(e.path().c_str(), &st) == 0) out[e.path().filename().string()] = st.st_ino;
        }
        return out;
    }
};

// Every generated skin layer the world's levels use, type by type: bit-identical rest positions,
// normals, indices, bindings and LBS weights.
void expect_same_skins(const World& a, const World& b) {
    ASSERT_EQ(a.scene().types.size(), b.scene().types.size());
    size_t compared = 0;
    for (size_t t = 0; t < a.scene().types.size(); ++t) {
        const CharacterGeometry& ga = *a.runtime(t).geometry_data;
        const CharacterGeometry& gb = *b.runtime(t).geometry_data;
        const GeometryController& levels = *a.runtime(t).geometry;
        for (uint8_t l = 0; l < levels.level_count(); ++l) {
            const GeomLod& lod = levels.level(l);
            if (lod.method != GeomMethod::SkinnedMesh && lod.method != GeomMethod::Layered && lod.method != GeomMethod::Subdivided)
                continue;
            const SkinLayer& x = ga.skin_layer(std::max<uint32_t>(3, lod.theta_steps), std::max<uint32_t>(2, lod.phi_steps));
            const SkinLayer& y = gb.skin_layer(std::max<uint32_t>(3, lod.theta_steps), std::max<uint32_t>(2, lod.phi_steps));
            const auto same = [](const auto& u, const auto& v) {
                return u.size() == v.size() && std::memcmp(u.data(), v.data(), u.size() * sizeof(u[0])) == 0;
            };
            EXPECT_TRUE(same(x.rest_positions, y.rest_positions)) << "type " << t << " level " << int(l);
            EXPECT_TRUE(same(x.rest_normals, y.rest_normals)) << "type " << t << " level " << int(l);
            EXPECT_TRUE(same(x.indices, y.indices)) << "type " << t << " level " << int(l);
            EXPECT_TRUE(same(x.bindings, y.bindings)) << "type " << t << " level " << int(l);
            EXPECT_TRUE(same(x.joints, y.joints) && same(x.weights, y.weights)) << "type " << t << " level " << int(l);
            ++compared;
        }
    }
    EXPECT_GT(compared, 0u);
}

void run(World& w, int frames) {
    for (int f = 0; f < frames; ++f) w.step();
}

// One test for the paths that bake (each cold world costs seconds): cold, warm, damaged, unusable.
TEST_F(WorldBakeCache, WarmDamagedAndUncachedWorldsAreBitIdenticalToTheColdOne) {
    const fs::path cache = dir / "cache";
    auto cold = make_world(scene, options(cache));
    ASSERT_TRUE(cold);
    const auto written = entries(cache);
    EXPECT_GE(written.size(), 2u);  // at least one skin layer per type
    WorldOptions warm_options = options(cache);
    warm_options.threads = 2;  // the types baked (here: read) two at a time: the same world
    auto warm = make_world(scene, warm_options);
    ASSERT_TRUE(warm);
    EXPECT_EQ(entries(cache), written);  // every entry read, none rebuilt or added
    expect_same_skins(*cold, *warm);

    // Truncate every entry: each is rejected (a message naming it) and rebuilt, the types baked two at a
    // time (the cold world baked them one by one).
    // (Two types with the same inputs, as the base type and its middle variant here, share entries.)
    std::map<std::string, uintmax_t> sizes;
    for (const auto& [name, inode] : written) {
        sizes[name] = fs::file_size(cache / name);
        fs::resize_file(cache / name, sizes[name] / 2);
    }
    auto rebuilt = make_world(scene, warm_options);
    ASSERT_TRUE(rebuilt);
    ASSERT_EQ(entries(cache).size(), written.size());
    for (const auto& [name, size] : sizes) EXPECT_EQ(fs::file_size(cache / name), size) << name << " was not rewritten whole";
    expect_same_skins(*cold, *rebuilt);

    // A directory below a regular file cannot be made: no cache (one message), the same world.
    std::ofstream(dir / "file") << "x";
    auto uncached = make_world(scene, options(dir / "file" / "cache"));
    ASSERT_TRUE(uncached);
    expect_same_skins(*cold, *uncached);

    for (World* w : {cold.get(), warm.get(), rebuilt.get(), uncached.get()}) run(*w, 30);
    EXPECT_EQ(state_hash(*cold), state_hash(*warm));
    EXPECT_EQ(state_hash(*cold), state_hash(*rebuilt));
    EXPECT_EQ(state_hash(*cold), state_hash(*uncached));
}

TEST_F(WorldBakeCache, CacheOffOpensNothing) {
    EXPECT_FALSE(open_bake_cache(false, (dir / "off").string()));
    EXPECT_FALSE(fs::exists(dir / "off"));
    EXPECT_TRUE(open_bake_cache(true, (dir / "on").string()));  // made on demand
    EXPECT_TRUE(fs::is_directory(dir / "on"));
}

TEST_F(WorldBakeCache, SizeLimitFromTheHostOrTheDefault) {
    const auto given = open_bake_cache(true, (dir / "on").string(), uint64_t{64} << 20);
    ASSERT_TRUE(given);
    EXPECT_EQ(given->max_bytes(), uint64_t{64} << 20);
    const auto unlimited = open_bake_cache(true, (dir / "on").string(), 0);
    ASSERT_TRUE(unlimited);
    EXPECT_EQ(unlimited->max_bytes(), 0u);
    const auto fallback = open_bake_cache(true, (dir / "on").string());
    ASSERT_TRUE(fallback);
    EXPECT_EQ(fallback->max_bytes(), default_cache_limit_bytes());
}

}  // namespace
}  // namespace aloha
