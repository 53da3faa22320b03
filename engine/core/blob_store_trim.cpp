// BlobStore's size limit: the least recently used entries removed while the store is over it, stale
// temporary files, and the limit from the environment.
#include "engine/core/blob_store.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace aloha {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kPrefix = "aloha-bake-";
constexpr std::string_view kSuffix = ".bin";
constexpr size_t kDigestChars = 32;
// A temporary file this old belongs to a write that never finished (a write takes milliseconds).
constexpr auto kStaleTemporary = std::chrono::hours(1);

// True for the name of an entry: "aloha-bake-" + 32 hexadecimal digits + ".bin" (BlobStore::entry_path).
bool is_entry_name(const std::string& name) {
    if (name.size() != kPrefix.size() + kDigestChars + kSuffix.size() || name.rfind(kPrefix, 0) != 0 ||
        name.compare(name.size() - kSuffix.size(), kSuffix.size(), kSuffix) != 0)
        return false;
    return std::all_of(name.begin() + static_cast<std::ptrdiff_t>(kPrefix.size()),
                       name.end() - static_cast<std::ptrdiff_t>(kSuffix.size()),
                       [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; });
}

// True for the name of a write's temporary file: an entry's (or the open probe's) name + ".tmp." + ...
bool is_temporary_name(const std::string& name) {
    return name.rfind(kPrefix, 0) == 0 && name.find(".tmp.") != std::string::npos;
}

struct Entry {
    fs::path path;
    fs::file_time_type used;
    uint64_t bytes = 0;
};

}  // namespace

BlobStoreTrim BlobStore::trim() const {
    const std::lock_guard<std::mutex> lock(trim_mutex_);
    BlobStoreTrim out;
    std::vector<Entry> entries;
    const auto now = fs::file_time_type::clock::now();
    std::error_code ec;
    for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code fe;
        if (!it->is_regular_file(fe) || fe) continue;
        const std::string name = it->path().filename().string();
        const fs::file_time_type when = it->last_write_time(fe);
        if (fe) continue;
        if (is_temporary_name(name)) {
            if (now - when > kStaleTemporary && fs::remove(it->path(), fe)) ++out.stale_temporaries;
            continue;
        }
        if (!is_entry_name(name)) continue;
        const uint64_t bytes = it->file_size(fe);
        if (fe) continue;
        entries.push_back({it->path(), when, bytes});
        out.bytes += bytes;
    }
    out.entries = entries.size();
    if (max_bytes_ == 0 || out.bytes <= max_bytes_) {
        known_bytes_.store(out.bytes);
        return out;
    }
    // Least recently used first; the most recent entry stays whatever its size.
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used || (a.used == b.used && a.path < b.path); });
    for (size_t i = 0; i + 1 < entries.size() && out.bytes > max_bytes_; ++i) {
        const Entry& e = entries[i];
        std::error_code fe;
        if (!is_entry(e.path) || !fs::remove(e.path, fe)) continue;  // a foreign file under an entry's name stays
        out.bytes -= e.bytes;
        --out.entries;
        ++out.removed;
        out.removed_bytes += e.bytes;
    }
    evicted_.fetch_add(out.removed);
    known_bytes_.store(out.bytes);
    return out;
}

std::optional<uint64_t> parse_cache_limit_mib(const std::string& text) {
    if (text.empty() || text.size() > 13 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return std::nullopt;
    const uint64_t mib = std::stoull(text);
    if (mib > (uint64_t{1} << 40)) return std::nullopt;
    return mib << 20;
}

uint64_t default_cache_limit_bytes(const BlobStoreLog& log) {
    const char* v = std::getenv("ALOHA_CACHE_MAX_MB");
    if (!v || !*v) return BlobStore::kDefaultMaxBytes;
    if (const std::optional<uint64_t> bytes = parse_cache_limit_mib(v)) return *bytes;
    const std::string message = std::string("bake cache: ALOHA_CACHE_MAX_MB='") + v +
                                "' is not a whole number of MiB (0 = no limit); using the default limit of " +
                                std::to_string(BlobStore::kDefaultMaxBytes >> 20) + " MiB";
    if (log)
        log(message);
    else
        std::fprintf(stderr, "%s\n", message.c_str());
    return BlobStore::kDefaultMaxBytes;
}

}  // namespace aloha
