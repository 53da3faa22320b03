// hash_bytes64: the bake cache's checksum and key digest.
#include "engine/core/byte_io.hpp"

namespace aloha {
namespace {

// splitmix64's finaliser (Steele, Lea, Flood 2014): every input bit reaches every output bit.
uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

}  // namespace

uint64_t hash_bytes64(std::span<const uint8_t> bytes, uint64_t seed) {
    uint64_t h = mix64(seed ^ 0x9e3779b97f4a7c15ull) ^ static_cast<uint64_t>(bytes.size());
    size_t i = 0;
    for (; i + 8 <= bytes.size(); i += 8) {
        uint64_t w;
        std::memcpy(&w, bytes.data() + i, 8);
        h = mix64(h ^ w) + 0x9e3779b97f4a7c15ull;
    }
    uint64_t tail = 0;
    if (i < bytes.size()) std::memcpy(&tail, bytes.data() + i, bytes.size() - i);
    return mix64(h ^ tail ^ (static_cast<uint64_t>(bytes.size() - i) << 56));
}

std::vector<uint8_t> digest_key(uint32_t kind, std::span<const uint8_t> inputs) {
    ByteWriter key;
    key.put(kind);
    key.put(hash_bytes64(inputs, 0x9e3779b97f4a7c15ull));
    key.put(hash_bytes64(inputs, 0xc2b2ae3d27d4eb4full));
    key.put<uint64_t>(inputs.size());
    return key.take();
}

}  // namespace aloha
