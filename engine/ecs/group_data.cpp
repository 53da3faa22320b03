#include "engine/ecs/group_data.hpp"

#include <cassert>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace aloha {

void key_ranges(std::span<const uint32_t> sorted_keys, std::vector<KeyRange>& out) {
    out.clear();
    size_t begin = 0;
    while (begin < sorted_keys.size()) {
        size_t end = begin + 1;
        while (end < sorted_keys.size() && sorted_keys[end] == sorted_keys[begin]) ++end;
        out.push_back(KeyRange{sorted_keys[begin], begin, end});
        begin = end;
    }
}

std::vector<KeyRange> key_ranges(std::span<const uint32_t> sorted_keys) {
    std::vector<KeyRange> out;
    key_ranges(sorted_keys, out);
    return out;
}

GroupData::GroupData(std::vector<StorageBase*> owned) : owned_(std::move(owned)) {
    assert(!owned_.empty());
    for (StorageBase* s : owned_) {
        if (s->owner() != nullptr) {
            // Programmer error even in release builds: two groups cannot both pack one storage.
            std::fprintf(stderr, "aloha: component type '%s' is already owned by another group\n",
                         std::string(type_name(s->type())).c_str());
            std::abort();
        }
        s->set_owner(this);
    }
    // Pack the entities that already have every owned component, driven by the smallest storage.
    const StorageBase* smallest = *std::min_element(
        owned_.begin(), owned_.end(), [](const StorageBase* a, const StorageBase* b) { return a->size() < b->size(); });
    const std::vector<Entity> candidates(smallest->entities().begin(), smallest->entities().end());
    for (const Entity e : candidates) on_construct(e);
}

GroupData::~GroupData() {
    for (StorageBase* s : owned_) s->set_owner(nullptr);
}

bool GroupData::owns_exactly(std::span<const ComponentTypeId> sorted_types) const {
    if (sorted_types.size() != owned_.size()) return false;
    std::vector<ComponentTypeId> mine;
    mine.reserve(owned_.size());
    for (const StorageBase* s : owned_) mine.push_back(s->type());
    std::sort(mine.begin(), mine.end());
    return std::equal(mine.begin(), mine.end(), sorted_types.begin());
}

void GroupData::on_construct(Entity e) {
    for (const StorageBase* s : owned_) {
        if (!s->contains(e)) return;
    }
    if (owned_.front()->index_of(e) < size_) return;  // already grouped
    for (StorageBase* s : owned_) s->swap_positions(s->index_of(e), size_);
    ++size_;
}

void GroupData::on_destroy(Entity e) {
    // Only a complete entity can be inside the group; check membership through any storage it is in.
    for (const StorageBase* s : owned_) {
        if (!s->contains(e)) return;
    }
    if (owned_.front()->index_of(e) >= size_) return;
    --size_;
    for (StorageBase* s : owned_) s->swap_positions(s->index_of(e), size_);
}

bool GroupData::sort_by_key(std::span<uint32_t> keys) {
    assert(keys.size() == size_);
    if (std::is_sorted(keys.begin(), keys.end())) return false;  // the cheap, common path
    const uint32_t max_key = *std::max_element(keys.begin(), keys.end());
    perm_.resize(size_);
    constexpr uint32_t kCountingSortLimit = 1u << 16;
    if (max_key < kCountingSortLimit) {
        // Counting sort: O(n + keys), stable.
        counts_.assign(size_t{max_key} + 2, 0);
        for (const uint32_t k : keys) ++counts_[k + 1];
        for (size_t k = 1; k < counts_.size(); ++k) counts_[k] += counts_[k - 1];
        for (uint32_t i = 0; i < size_; ++i) perm_[counts_[keys[i]]++] = i;
    } else {
        std::iota(perm_.begin(), perm_.end(), 0u);
        std::stable_sort(perm_.begin(), perm_.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
    }
    sorted_keys_.resize(size_);
    for (size_t i = 0; i < size_; ++i) sorted_keys_[i] = keys[perm_[i]];
    std::copy(sorted_keys_.begin(), sorted_keys_.end(), keys.begin());
    return apply_permutation(perm_);
}

bool GroupData::partition_by_key(std::span<uint32_t> keys) {
    assert(keys.size() == size_);
    if (std::is_sorted(keys.begin(), keys.end())) return false;
    const uint32_t max_key = *std::max_element(keys.begin(), keys.end());
    constexpr uint32_t kBucketLimit = 1u << 16;
    if (max_key >= kBucketLimit) return sort_by_key(keys);
    // Bucket b occupies [start(b), start(b+1)); next_[b] is the first position of bucket b not
    // yet known to hold key b.
    counts_.assign(size_t{max_key} + 2, 0);
    for (const uint32_t k : keys) ++counts_[k + 1];
    for (size_t k = 1; k < counts_.size(); ++k) counts_[k] += counts_[k - 1];
    next_.assign(counts_.begin(), counts_.end() - 1);
    swaps_.clear();
    for (uint32_t b = 0; b <= max_key; ++b) {
        const uint32_t end = counts_[b + 1];
        for (uint32_t i = next_[b]; i < end; i = ++next_[b]) {
            // Swap whatever sits at i into its own bucket until i holds key b: every swap puts
            // one element in its final bucket, so there are at most n swaps in total.
            while (keys[i] != b) {
                const uint32_t t = keys[i];
                while (keys[next_[t]] == t) ++next_[t];
                const uint32_t j = next_[t]++;
                std::swap(keys[i], keys[j]);
                swaps_.push_back(SwapPair{i, j});
            }
        }
    }
    if (swaps_.empty()) return false;
    for (StorageBase* s : owned_) s->apply_swaps(swaps_);
    return true;
}

bool GroupData::apply_permutation(std::span<const uint32_t> perm) {
    assert(perm.size() == size_);
    // Decompose into swaps along each cycle: swap(j, perm[j]) for j = i, perm[i], ... puts
    // old[perm[j]] at j. Elements already in place cost nothing.
    swaps_.clear();
    visited_.assign(perm.size(), 0);
    for (uint32_t i = 0; i < perm.size(); ++i) {
        if (visited_[i] != 0 || perm[i] == i) continue;
        uint32_t j = i;
        visited_[j] = 1;
        while (perm[j] != i) {
            swaps_.push_back(SwapPair{j, perm[j]});
            j = perm[j];
            visited_[j] = 1;
        }
    }
    if (swaps_.empty()) return false;
    for (StorageBase* s : owned_) s->apply_swaps(swaps_);
    return true;
}

}  // namespace aloha
