#include "engine/ecs/slot_table.hpp"

#include <algorithm>
#include <array>
#include <cassert>

namespace aloha {

bool SlotTable::current(std::span<const uint64_t> versions) const {
    return built_ && std::equal(versions.begin(), versions.end(), versions_.begin(), versions_.end());
}

void SlotTable::reset(std::span<const uint64_t> versions) {
    columns_ = versions.size();
    driver_ = 0;
    driver_storage_ = nullptr;
    used_rows_ = 0;
    segments_.clear();
    versions_.assign(versions.begin(), versions.end());
    built_ = true;
    ++rebuilds_;
}

void SlotTable::build_empty(std::span<const uint64_t> versions) { reset(versions); }

size_t SlotTable::count() const {
    size_t n = used_rows_;
    for (const Segment& s : segments_) n += s.aligned ? s.end - s.begin : 0;
    return n;
}

void SlotTable::build(std::span<const StorageBase* const> storages, std::span<const uint64_t> versions) {
    assert(!storages.empty() && storages.size() <= kMaxColumns);
    reset(versions);
    size_t driver = 0;
    for (size_t s = 1; s < storages.size(); ++s) driver = storages[s]->size() < storages[driver]->size() ? s : driver;
    driver_ = driver;
    driver_storage_ = storages[driver];
    // At most one entry per driver entity; grown (never shrunk) so rebuilds reuse the memory.
    const size_t n = storages[driver]->size();
    if (rows_.size() < n * columns_) rows_.resize(n * columns_);
    switch (columns_) {
        case 1: walk<1>(storages, driver); break;
        case 2: walk<2>(storages, driver); break;
        case 3: walk<3>(storages, driver); break;
        case 4: walk<4>(storages, driver); break;
        default: walk<0>(storages, driver); break;
    }
}

// Walks the driving storage, looks every entity up in the others (index and generation) and records
// matches: same-position stretches of at least kMinRange as ranges, the rest as entries.
template <size_t kCols>
void SlotTable::walk(std::span<const StorageBase* const> storages, size_t driver) {
    const size_t cols = kCols != 0 ? kCols : columns_;
    constexpr size_t kRoom = kCols != 0 ? kCols : kMaxColumns;
    std::vector<SparseIndex> sparse;
    sparse.reserve(cols);
    for (const StorageBase* s : storages) sparse.push_back(s->sparse());
    const std::span<const Entity> ents = storages[driver]->entities();
    const auto n = static_cast<uint32_t>(ents.size());
    std::array<uint32_t, kRoom> row{};     // the entity being looked at
    std::array<uint32_t, kRoom> in_run{};  // an entry of a stretch too short for a range
    uint32_t run_begin = 0;  // start of the current same-position stretch
    uint32_t run_end = 0;
    auto close_run = [&] {
        if (run_end - run_begin >= kMinRange) {
            segments_.push_back(Segment{run_begin, run_end, true});
        } else {
            for (uint32_t k = run_begin; k < run_end; ++k) {
                std::fill(in_run.begin(), in_run.end(), k);
                append_row<kCols>(in_run.data());
            }
        }
        run_begin = run_end;
    };
    for (uint32_t k = 0; k < n; ++k) {
        if (k + kAhead < n) {
            for (size_t s = 0; s < cols; ++s) {
                if (s == driver) continue;
                detail::prefetch<false>(sparse[s].position_slot(ents[k + kAhead].index));
                detail::prefetch<false>(sparse[s].generation_slot(ents[k + kAhead].index));
            }
        }
        bool present = true;
        bool aligned = true;
        for (size_t s = 0; s < cols; ++s) {
            row[s] = s == driver ? k : sparse[s].find(ents[k]);
            present &= row[s] != StorageBase::kAbsent;
            aligned &= row[s] == k;
        }
        if (aligned) {
            run_end = k + 1;  // extends the stretch (every path leaves run_end == k + 1)
            continue;
        }
        close_run();
        run_begin = run_end = k + 1;
        if (present) append_row<kCols>(row.data());
    }
    close_run();
}

template <size_t kCols>
void SlotTable::append_row(const uint32_t* row) {
    const size_t cols = kCols != 0 ? kCols : columns_;
    const auto at = static_cast<uint32_t>(used_rows_);
    if (segments_.empty() || segments_.back().aligned) segments_.push_back(Segment{at, at, false});
    uint32_t* out = rows_.data() + used_rows_ * cols;
    for (size_t c = 0; c < cols; ++c) out[c] = row[c];
    ++used_rows_;
    ++segments_.back().end;
}

}  // namespace aloha
