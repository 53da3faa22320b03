// The bake cache's part of `aloha profile`'s report and table.
#include "host/tool/profile_cache.hpp"

#include <cstdio>

namespace aloha {

nlohmann::json bake_cache_report(const World& world) {
    const BlobStore* cache = world.bake_cache();
    if (cache == nullptr) return nullptr;
    std::string version;
    for (const uint8_t b : cache->code_version()) {
        char hex[3];
        std::snprintf(hex, sizeof(hex), "%02x", b);
        version += hex;
    }
    const BlobStoreCounts c = cache->counts();
    return {{"directory", cache->directory().string()}, {"code_version", version}, {"hits", c.hits},
            {"misses", c.misses}, {"rejected", c.rejected}, {"writes", c.writes}, {"evicted", c.evicted}};
}

std::string bake_cache_line(const World& world) {
    const BlobStore* cache = world.bake_cache();
    if (cache == nullptr) return "";
    const BlobStoreCounts c = cache->counts();
    return "bake cache " + cache->directory().string() + ": " + std::to_string(c.hits) + " read, " + std::to_string(c.misses) +
           " missing, " + std::to_string(c.rejected) + " rejected, " + std::to_string(c.writes) + " written\n";
}

}  // namespace aloha
