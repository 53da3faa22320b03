// make_character_runtimes: a scene's character types built in parallel (each type's geometry is
// independent of the others'), and the bake cache the World opens for them.
#include "host/scene/character_runtime.hpp"

#include "systems/geometry/controller/skin_bake.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <thread>

namespace aloha {

Result<std::vector<std::unique_ptr<CharacterRuntime>>> make_character_runtimes(const SceneDesc& scene,
                                                                               std::span<const CharacterDesc> chars,
                                                                               std::span<const GeomLod> levels,
                                                                               bool keep_refined_surfaces,
                                                                               const TypeLoadOptions& load) {
    const size_t types = scene.types.size();
    std::vector<uint32_t> per_type(types, 0);
    for (const auto& c : chars) per_type[static_cast<size_t>(c.type)]++;
    std::vector<std::unique_ptr<CharacterRuntime>> out(types);
    std::vector<std::optional<Error>> errors(types);
    // Type t only writes out[t] and errors[t]: the result is the same whichever thread builds which type.
    const auto build = [&](size_t t) {
        auto type = load_character_type(scene.types[t]);
        if (!type.ok()) {
            errors[t] = type.error();
            return;
        }
        auto rt = std::make_unique<CharacterRuntime>(std::move(type.value()), per_type[t]);
        rt->add_paths(scene);
        if (Status s = rt->init_geometry(static_cast<uint16_t>(t), levels, keep_refined_surfaces, load.bake_cache); !s.ok()) {
            errors[t] = s.error();
            return;
        }
        rt->measure_bounds(levels);
        out[t] = std::move(rt);
    };
    // oneTBB as the scheduler uses it: an arena of `threads` (0 = every core), one type per task.
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const size_t workers = std::max<size_t>(1, std::min<size_t>(types, load.threads == 0 ? cores : load.threads));
    tbb::task_arena arena(static_cast<int>(workers));
    arena.execute([&] { tbb::parallel_for(size_t{0}, types, size_t{1}, build); });
    for (size_t t = 0; t < types; ++t)
        if (errors[t]) return *errors[t];
    return out;
}

std::shared_ptr<const BlobStore> open_bake_cache(bool enabled, const std::optional<std::string>& dir, std::optional<uint64_t> max_bytes) {
    if (!enabled) return nullptr;
    const std::optional<std::filesystem::path> where = dir ? std::optional<std::filesystem::path>(*dir) : default_cache_directory();
    if (!where) {
        std::fprintf(stderr, "bake cache: no directory (set ALOHA_CACHE_DIR, XDG_CACHE_HOME or HOME); loading without the cache\n");
        return nullptr;
    }
    const Result<std::vector<uint8_t>> version = skin_bake_code_version();
    if (!version.ok()) {
        // Once per process: the version is computed once and fails the same way every time.
        static std::atomic<bool> said{false};
        if (!said.exchange(true))
            std::fprintf(stderr, "bake cache: off, no code version: %s\n", version.error().to_string().c_str());
        return nullptr;
    }
    return BlobStore::open(*where, version.value(), {}, max_bytes ? *max_bytes : default_cache_limit_bytes());
}

}  // namespace aloha
