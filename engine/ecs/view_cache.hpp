// ViewCache: the slot table the registry keeps for one list of component types, so that
// Registry::view<Ts...>().each() on storages whose layout has not changed reads recorded positions
// instead of looking every entity up again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

#include "engine/ecs/slot_table.hpp"
#include "engine/ecs/storage_base.hpp"
#include "engine/ecs/type_id.hpp"

namespace aloha {

/// One registry's cached matches for one list of component types (constness ignored, order kept:
/// column c is the c-th type, and the iteration order is the stateless View's for that list).
/// The policy, applied by acquire() on every View::each():
/// - the table was built at the storages' current layout versions: each() reads the table;
/// - otherwise, when the previous acquire() saw exactly these versions (the layout has stayed put
///   across two calls), the table is built now and read;
/// - otherwise (the first call after a structural change) each() runs the stateless loop and the
///   versions are remembered, so a layout that changes before every call never pays for a build.
/// acquire() is thread-safe (a mutex guards the check and the build); the table it returns is only
/// read until the next structural change, which the registry's contract keeps out of any iteration.
class ViewCache {
public:
    /// A cache for the types `key` over `storages` (same length, none null; they must outlive it).
    ViewCache(std::span<const ComponentTypeId> key, std::span<const StorageBase* const> storages);
    ViewCache(const ViewCache&) = delete;
    ViewCache& operator=(const ViewCache&) = delete;

    /// True when this cache is for exactly the type list `key`.
    [[nodiscard]] bool is_for(std::span<const ComponentTypeId> key) const;
    /// The table to iterate when it matches the storages' layouts now (built here when the previous
    /// call saw the same layouts), or nullptr: then iterate without it. Thread-safe.
    [[nodiscard]] const SlotTable* acquire();

    /// How many times the table has been built.
    [[nodiscard]] size_t builds() const;
    /// Calls of acquire() that returned the table.
    [[nodiscard]] size_t table_calls() const;
    /// Calls of acquire() that returned nullptr (stateless iteration).
    [[nodiscard]] size_t stateless_calls() const;

private:
    mutable std::mutex mutex_;
    std::vector<ComponentTypeId> key_;
    std::vector<const StorageBase*> storages_;
    SlotTable table_;
    std::vector<uint64_t> now_;   // scratch: the storages' versions at this call
    std::vector<uint64_t> seen_;  // versions the last stateless call saw (empty: none yet)
    size_t table_calls_ = 0;
    size_t stateless_calls_ = 0;
};

}  // namespace aloha
