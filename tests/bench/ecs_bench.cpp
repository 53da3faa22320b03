// ECS iteration over two packed components (Position += Velocity * dt) via the registry's (cached)
// View, a stateless View, a Query, Group spans, and a plain struct-of-arrays loop, the lower bound.
// Reported per entity (ns_per_entity), or per entity the view visits (ns_per_match) where only some
// entities match.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/ecs/command_buffer.hpp"
#include "engine/ecs/registry.hpp"

namespace {

struct Position {
    float x = 0, y = 0, z = 0;
};
struct Velocity {
    float x = 0, y = 0, z = 0;
};
constexpr float kDt = 1.0f / 60.0f;

void Populate(aloha::Registry& r, int64_t n) {
    r.reserve(size_t(n));
    r.storage<Position>().reserve(size_t(n));
    r.storage<Velocity>().reserve(size_t(n));
    for (int64_t i = 0; i < n; ++i) {
        const aloha::Entity e = r.create();
        r.emplace<Position>(e, float(i), 0.0f, 0.0f);
        r.emplace<Velocity>(e, 1.0f, 2.0f, 3.0f);
    }
}

void SetPerEntity(benchmark::State& state) {
    state.SetItemsProcessed(int64_t(state.iterations()) * state.range(0));
    state.counters["ns_per_entity"] = benchmark::Counter(
        double(state.range(0)), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The benchmarked work: Position += Velocity * dt through `view` (a View or a Query).
template <class ViewT>
void UpdatePositions(ViewT&& view) {
    view.each([](Position& p, const Velocity& v) {
        p.x += v.x * kDt;
        p.y += v.y * kDt;
        p.z += v.z * kDt;
    });
}

// How the benchmarked loop reaches the components:
// - kView: `r.view<...>().each(...)` on every pass, as a system calls it. The registry's ViewCache
//   reads its slot table once the layout has stayed put across two calls; the two calls before timing
//   get it there, so this is the steady state (the first call after a structural change is the
//   ChangedEachPass cases below);
// - kStatelessView: a View built from the storages (no cache), which looks every match up each pass;
// - kQuery: a Query kept across passes (looks them up once, then reads its slot table; built before timing).
enum class Access { kView, kStatelessView, kQuery };

// Runs UpdatePositions over r's Position + const Velocity through `access` for every iteration.
template <Access access>
void IteratePositions(benchmark::State& state, aloha::Registry& r) {
    if constexpr (access == Access::kView) {
        for (int warm = 0; warm < 2; ++warm) (void)r.view<Position, const Velocity>().count();
        for (auto _ : state) {
            UpdatePositions(r.view<Position, const Velocity>());
            benchmark::ClobberMemory();
        }
        const aloha::ViewCache* cache = r.view<Position, const Velocity>().cache();
        if (cache == nullptr || cache->builds() != 1) state.SkipWithError("view cache not built exactly once");
    } else if constexpr (access == Access::kStatelessView) {
        const aloha::View<Position, const Velocity> view(&r.storage<Position>(), &r.storage<Velocity>());
        for (auto _ : state) {
            UpdatePositions(view);
            benchmark::ClobberMemory();
        }
    } else {
        auto query = r.query<Position, const Velocity>();
        (void)query.count();  // builds the slot table
        for (auto _ : state) {
            UpdatePositions(query);
            benchmark::ClobberMemory();
        }
        if (query.rebuilds() != 1) state.SkipWithError("query rebuilt on unchanged storages");
    }
}

template <Access access>
void BM_AllMatch(benchmark::State& state) {
    aloha::Registry r;
    Populate(r, state.range(0));
    IteratePositions<access>(state, r);
    SetPerEntity(state);
}

// Every entity has Position; 10% of them also get Velocity, added in creation order: a random 10%
// (Bernoulli, fixed seed) when range(1) is 0, every tenth entity when it is 1. The loop visits only
// those, so the figure is ns per matching entity.
int64_t PopulateTenPercent(aloha::Registry& r, int64_t n, bool strided) {
    r.reserve(size_t(n));
    r.storage<Position>().reserve(size_t(n));
    std::mt19937 rng(2);
    std::bernoulli_distribution has_velocity(0.1);
    int64_t matches = 0;
    for (int64_t i = 0; i < n; ++i) {
        const aloha::Entity e = r.create();
        r.emplace<Position>(e, float(i), 0.0f, 0.0f);
        if (strided ? i % 10 == 0 : has_velocity(rng)) {
            r.emplace<Velocity>(e, 1.0f, 2.0f, 3.0f);
            ++matches;
        }
    }
    return matches;
}

void SetPerMatch(benchmark::State& state, int64_t matches) {
    state.SetItemsProcessed(int64_t(state.iterations()) * matches);
    state.counters["ns_per_match"] = benchmark::Counter(
        double(matches), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <Access access>
void BM_TenPercent(benchmark::State& state) {
    aloha::Registry r;
    const int64_t matches = PopulateTenPercent(r, state.range(0), state.range(1) != 0);
    if (r.view<Position, const Velocity>().count() != size_t(matches)) state.SkipWithError("view visits the wrong entities");
    IteratePositions<access>(state, r);
    SetPerMatch(state, matches);
}

// The Query's worst case: the random 10% with one structural change before every pass (one entity's
// Velocity removed and put back), so every pass rebuilds the slot table before iterating.
void BM_QueryTenPercentRebuiltEachPass(benchmark::State& state) {
    aloha::Registry r;
    const int64_t matches = PopulateTenPercent(r, state.range(0), false);
    auto query = r.query<Position, const Velocity>();
    const aloha::Entity moved = r.storage<Velocity>().entities()[0];
    for (auto _ : state) {
        r.remove<Velocity>(moved);
        r.emplace<Velocity>(moved, 1.0f, 2.0f, 3.0f);
        UpdatePositions(query);
        benchmark::ClobberMemory();
    }
    if (query.rebuilds() != size_t(state.iterations())) state.SkipWithError("query did not rebuild each pass");
    SetPerMatch(state, matches);
}

// The first call after a structural change, every pass: one entity's Velocity removed and put back
// before each `r.view<...>().each(...)`, so the registry's cache is never current and the view runs
// its stateless loop (what a system gets on the frame after entities were added, removed or moved).
void ViewChangedEachPass(benchmark::State& state, aloha::Registry& r) {
    const aloha::Entity moved = r.storage<Velocity>().entities()[0];
    for (auto _ : state) {
        r.remove<Velocity>(moved);
        r.emplace<Velocity>(moved, 1.0f, 2.0f, 3.0f);
        UpdatePositions(r.view<Position, const Velocity>());
        benchmark::ClobberMemory();
    }
    const aloha::ViewCache* cache = r.view<Position, const Velocity>().cache();
    if (cache == nullptr || cache->builds() != 0) state.SkipWithError("view cache built on a changing layout");
}

void BM_ViewTenPercentChangedEachPass(benchmark::State& state) {
    aloha::Registry r;
    const int64_t matches = PopulateTenPercent(r, state.range(0), false);
    ViewChangedEachPass(state, r);
    SetPerMatch(state, matches);
}

// Every entity has both components, but each storage is filled in its own shuffled order, so the two
// dense orders disagree: the stateless view's lookup of every entity in the other storage's sparse page
// is a random access, and so (for every access kind) is the component it finds there.
void PopulateShuffled(aloha::Registry& r, int64_t n) {
    std::vector<aloha::Entity> es;
    for (int64_t i = 0; i < n; ++i) es.push_back(r.create());
    std::mt19937 rng(1);
    std::shuffle(es.begin(), es.end(), rng);
    for (const aloha::Entity e : es) r.emplace<Position>(e);
    std::shuffle(es.begin(), es.end(), rng);
    for (const aloha::Entity e : es) r.emplace<Velocity>(e, 1.0f, 2.0f, 3.0f);
}

template <Access access>
void BM_Shuffled(benchmark::State& state) {
    aloha::Registry r;
    PopulateShuffled(r, state.range(0));
    IteratePositions<access>(state, r);
    SetPerEntity(state);
}

void BM_ViewShuffledChangedEachPass(benchmark::State& state) {
    aloha::Registry r;
    PopulateShuffled(r, state.range(0));
    ViewChangedEachPass(state, r);
    SetPerEntity(state);
}

void BM_View(benchmark::State& state) { BM_AllMatch<Access::kView>(state); }
void BM_ViewStateless(benchmark::State& state) { BM_AllMatch<Access::kStatelessView>(state); }
void BM_Query(benchmark::State& state) { BM_AllMatch<Access::kQuery>(state); }
void BM_ViewTenPercent(benchmark::State& state) { BM_TenPercent<Access::kView>(state); }
void BM_ViewStatelessTenPercent(benchmark::State& state) { BM_TenPercent<Access::kStatelessView>(state); }
void BM_QueryTenPercent(benchmark::State& state) { BM_TenPercent<Access::kQuery>(state); }
void BM_ViewShuffled(benchmark::State& state) { BM_Shuffled<Access::kView>(state); }
void BM_ViewStatelessShuffled(benchmark::State& state) { BM_Shuffled<Access::kStatelessView>(state); }
void BM_QueryShuffled(benchmark::State& state) { BM_Shuffled<Access::kQuery>(state); }

void BM_GroupSpans(benchmark::State& state) {
    aloha::Registry r;
    Populate(r, state.range(0));
    auto group = r.group<Position, Velocity>();
    for (auto _ : state) {
        const auto pos = group.span<Position>();
        const auto vel = group.span<Velocity>();
        for (size_t i = 0; i < pos.size(); ++i) {
            pos[i].x += vel[i].x * kDt;
            pos[i].y += vel[i].y * kDt;
            pos[i].z += vel[i].z * kDt;
        }
        benchmark::ClobberMemory();
    }
    SetPerEntity(state);
}

void BM_PlainSoA(benchmark::State& state) {
    std::vector<Position> pos(size_t(state.range(0)));
    std::vector<Velocity> vel(size_t(state.range(0)), Velocity{1.0f, 2.0f, 3.0f});
    for (auto _ : state) {
        for (size_t i = 0; i < pos.size(); ++i) {
            pos[i].x += vel[i].x * kDt;
            pos[i].y += vel[i].y * kDt;
            pos[i].z += vel[i].z * kDt;
        }
        benchmark::ClobberMemory();
    }
    SetPerEntity(state);
}

// Cost of keeping a group ordered by LOD level when 1% of the keys change per frame, with `reorder`
// the group's stable sort or its minimal-move partition (each level still one contiguous range).
template <class Reorder>
void ReorderOnePercent(benchmark::State& state, Reorder reorder) {
    aloha::Registry r;
    Populate(r, state.range(0));
    auto group = r.group<Position, Velocity>();
    std::vector<uint32_t> keys(group.size());
    for (size_t i = 0; i < keys.size(); ++i) keys[i] = uint32_t(i % 4);
    reorder(group, keys);
    std::mt19937 rng(3);
    for (auto _ : state) {
        for (size_t k = 0; k < keys.size() / 100; ++k) keys[rng() % keys.size()] = uint32_t(rng() % 4);
        reorder(group, keys);
    }
    SetPerEntity(state);
}

void BM_GroupResortOnePercent(benchmark::State& state) {
    ReorderOnePercent(state, [](auto& group, std::vector<uint32_t>& keys) { group.sort_by_key(keys); });
}

void BM_GroupRepartitionOnePercent(benchmark::State& state) {
    ReorderOnePercent(state, [](auto& group, std::vector<uint32_t>& keys) { group.partition_by_key(keys); });
}

void BM_CreateDestroyWithCommands(benchmark::State& state) {
    aloha::Registry r;
    aloha::CommandBuffer cmds;
    std::vector<aloha::Entity> es;
    for (auto _ : state) {
        for (int64_t i = 0; i < state.range(0); ++i) {
            const aloha::Entity e = cmds.spawn();
            cmds.add<Position>(e, Position{});
            cmds.add<Velocity>(e, Velocity{});
        }
        cmds.apply(r);
        for (const aloha::Entity e : cmds.spawned()) cmds.despawn(e);
        cmds.apply(r);
    }
    SetPerEntity(state);
}

}  // namespace

// The 10% cases' sizes: random at 100k and 1M, every tenth at 1M.
void TenPercentArgs(benchmark::internal::Benchmark* b) {
    b->ArgNames({"n", "strided"})->Args({100'000, 0})->Args({1'000'000, 0})->Args({1'000'000, 1});
}

BENCHMARK(BM_PlainSoA)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_GroupSpans)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_View)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_ViewStateless)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_Query)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_ViewTenPercent)->Apply(TenPercentArgs);
BENCHMARK(BM_ViewStatelessTenPercent)->Apply(TenPercentArgs);
BENCHMARK(BM_ViewTenPercentChangedEachPass)->Arg(1'000'000);
BENCHMARK(BM_QueryTenPercent)->Apply(TenPercentArgs);
BENCHMARK(BM_QueryTenPercentRebuiltEachPass)->Arg(1'000'000);
BENCHMARK(BM_ViewShuffled)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_ViewStatelessShuffled)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_ViewShuffledChangedEachPass)->Arg(1'000'000);
BENCHMARK(BM_QueryShuffled)->Arg(10'000)->Arg(100'000)->Arg(1'000'000);
BENCHMARK(BM_GroupResortOnePercent)->Arg(10'000)->Arg(100'000);
BENCHMARK(BM_GroupRepartitionOnePercent)->Arg(10'000)->Arg(100'000);
BENCHMARK(BM_CreateDestroyWithCommands)->Arg(10'000);
BENCHMARK_MAIN();
