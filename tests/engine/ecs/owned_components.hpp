// Test components that remember their owning entity, so a component reached through a wrong (stale)
// slot shows, and a helper that fills a registry with them. Shared by the Query and ViewCache tests.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/ecs/registry.hpp"

namespace aloha::test {

/// A component holding its owner's handle bits and a visit counter.
struct Owned {
    uint64_t owner = 0;
    int hits = 0;
};
/// A second component holding its owner's handle bits.
struct Tagged {
    uint64_t owner = 0;
};
/// A third one, for storages a view does not use.
struct Extra {
    uint64_t owner = 0;
};

/// Creates `n` entities, each with Owned and those whose creation index passes `tagged` with Tagged
/// too; returns them in creation order.
template <class Pred>
std::vector<Entity> PopulateOwned(Registry& r, int n, Pred tagged) {
    std::vector<Entity> es;
    for (int i = 0; i < n; ++i) {
        const Entity e = r.create();
        es.push_back(e);
        r.emplace<Owned>(e, Owned{e.bits(), 0});
        if (tagged(i)) r.emplace<Tagged>(e, e.bits());
    }
    return es;
}

}  // namespace aloha::test
