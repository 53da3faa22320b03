// The bake cache's part of `aloha profile`'s report and table: where it is, which code version its entries are for
// and what this run read and wrote.
#pragma once

#include "host/scene/world.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace aloha {

/// report.json's "bake_cache": null when the cache is off, else {"directory", "code_version" (hexadecimal: the
/// version of the entries the store reads and writes, skin_bake_code_version()), "hits", "misses", "rejected", "writes", "evicted"}.
[[nodiscard]] nlohmann::json bake_cache_report(const World& world);

/// The table's line ("bake cache DIR: N read, M missing, R rejected, W written\n"), or "" when the cache is off.
[[nodiscard]] std::string bake_cache_line(const World& world);

}  // namespace aloha
