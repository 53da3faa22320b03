// Stable 64-bit hashing (FNV-1a) for determinism checks: the final state hash of a run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace aloha {

/// Incremental FNV-1a hash. Feeding the same bytes in the same order gives the same value on
/// every run and thread count.
class StateHasher {
public:
    /// Mixes `size` raw bytes at `data` into the hash.
    void add_bytes(const void* data, size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) {
            hash_ ^= p[i];
            hash_ *= 1099511628211ull;
        }
    }
    /// Mixes a trivially copyable value.
    template <class T>
    void add(const T& value) { add_bytes(&value, sizeof(T)); }
    /// Mixes every element of a span of trivially copyable values.
    template <class T>
    void add_span(std::span<const T> values) { add_bytes(values.data(), values.size_bytes()); }
    /// The current hash value.
    [[nodiscard]] uint64_t value() const { return hash_; }

private:
    uint64_t hash_ = 1469598103934665603ull;
};

}  // namespace aloha
