// BlobStore: entry names, the header, atomic writes and the checks that reject a bad entry.
#include "engine/core/blob_store.hpp"

#include "engine/core/byte_io.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <thread>

namespace aloha {
namespace {

namespace fs = std::filesystem;

// The fixed part of an entry: magic, format version, header size, key and payload lengths, checksum.
struct Header {
    char magic[8] = {};
    uint32_t format_version = 0;
    uint32_t header_size = 0;
    uint64_t key_length = 0;
    uint64_t payload_length = 0;
    uint64_t checksum = 0;
};
static_assert(sizeof(Header) == 40);

// Checksum of an entry's key and payload.
uint64_t checksum_of(std::span<const uint8_t> key, std::span<const uint8_t> payload) {
    return hash_bytes64(payload, hash_bytes64(key, 1));
}

// Reads a whole file; nothing when it cannot be opened (it does not exist, most often).
std::optional<std::vector<uint8_t>> read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) return std::nullopt;
    in.seekg(0, std::ios::beg);
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) return std::nullopt;
    return bytes;
}

// Writes `parts` to a new file `path`; false with errno's text in `why` on failure.
bool write_new_file(const fs::path& path, std::span<const std::span<const uint8_t>> parts, std::string& why) {
    std::FILE* f = std::fopen(path.c_str(), "wbx");  // x: never open an existing file
    if (!f) {
        why = std::strerror(errno);
        return false;
    }
    bool ok = true;
    for (const auto& part : parts) ok = ok && (part.empty() || std::fwrite(part.data(), 1, part.size(), f) == part.size());
    if (!ok) why = std::strerror(errno);
    if (std::fclose(f) != 0 && ok) {
        why = std::strerror(errno);
        ok = false;
    }
    return ok;
}

// A name for this write's temporary file: unique across processes (pid) and threads (counter).
std::string temporary_name(const fs::path& entry) {
    static std::atomic<uint64_t> counter{0};
    return entry.filename().string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
}

}  // namespace

std::shared_ptr<BlobStore> BlobStore::open(const fs::path& dir, std::vector<uint8_t> code_version, BlobStoreLog log,
                                           uint64_t max_bytes) {
    std::shared_ptr<BlobStore> store(new BlobStore());
    store->dir_ = dir;
    store->max_bytes_ = max_bytes;
    store->code_version_ = std::move(code_version);
    store->log_ = std::move(log);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir, ec)) {
        store->say("bake cache: cannot use directory '" + dir.string() + "' (" + (ec ? ec.message() : "not a directory") +
                   "); loading without the cache");
        return nullptr;
    }
    // Writable? A probe file made and removed (permission bits alone do not say: root, read-only mounts).
    const fs::path probe = dir / temporary_name(dir / "aloha-bake-probe");
    std::string why;
    const bool writable = write_new_file(probe, {}, why);
    fs::remove(probe, ec);
    if (!writable) {
        store->say("bake cache: cannot write in directory '" + dir.string() + "' (" + why + "); loading without the cache");
        return nullptr;
    }
    (void)store->trim();
    return store;
}

bool BlobStore::is_entry(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    return in.read(magic, 8) && std::memcmp(magic, kMagic, 8) == 0;
}

void BlobStore::say(const std::string& message) const {
    if (log_)
        log_(message);
    else
        std::fprintf(stderr, "%s\n", message.c_str());
}

fs::path BlobStore::entry_path(std::span<const uint8_t> key) const {
    // 128-bit digest of (code version, key): two independently seeded 64-bit hashes.
    ByteWriter w;
    w.put_vector(std::span<const uint8_t>(code_version_));
    w.put_bytes(key.data(), key.size());
    char name[64];
    std::snprintf(name, sizeof name, "aloha-bake-%016llx%016llx.bin",
                  static_cast<unsigned long long>(hash_bytes64(w.bytes(), 0x51ed270b27c4a3d1ull)),
                  static_cast<unsigned long long>(hash_bytes64(w.bytes(), 0x2545f4914f6cdd1dull)));
    return dir_ / name;
}

std::optional<std::vector<uint8_t>> BlobStore::get(std::span<const uint8_t> key) const {
    const fs::path path = entry_path(key);
    std::optional<std::vector<uint8_t>> bytes = read_file(path);
    if (!bytes) {
        misses_.fetch_add(1);
        return std::nullopt;
    }
    ByteWriter full_key;
    full_key.put_vector(std::span<const uint8_t>(code_version_));
    full_key.put_bytes(key.data(), key.size());
    const std::vector<uint8_t>& k = full_key.bytes();
    const auto reject = [&](const std::string& why) {
        rejected_.fetch_add(1);
        say("bake cache: entry '" + path.string() + "' " + why + "; rebuilding it");
        return std::nullopt;
    };
    Header h;
    if (bytes->size() < sizeof h) return reject("is truncated (" + std::to_string(bytes->size()) + " bytes, shorter than its header)");
    std::memcpy(&h, bytes->data(), sizeof h);
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0) return reject("is not a bake cache entry (wrong magic)");
    if (h.format_version != kFormatVersion)
        return reject("has format version " + std::to_string(h.format_version) + ", this program reads " + std::to_string(kFormatVersion));
    if (h.header_size != sizeof h || h.key_length > bytes->size() || h.payload_length > bytes->size() ||
        sizeof h + h.key_length + h.payload_length != bytes->size())
        return reject("is truncated or padded (" + std::to_string(bytes->size()) + " bytes, its header says " +
                      std::to_string(sizeof h + h.key_length + h.payload_length) + ")");
    const std::span<const uint8_t> stored_key(bytes->data() + sizeof h, h.key_length);
    const std::span<const uint8_t> payload(bytes->data() + sizeof h + h.key_length, h.payload_length);
    if (checksum_of(stored_key, payload) != h.checksum) return reject("is corrupt (checksum mismatch)");
    if (stored_key.size() != k.size() || std::memcmp(stored_key.data(), k.data(), k.size()) != 0)
        return reject("holds another key (a digest collision)");
    hits_.fetch_add(1);
    // Used now: the trim removes the entries used longest ago first.
    std::error_code ec;
    fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
    return std::vector<uint8_t>(payload.begin(), payload.end());
}

void BlobStore::put(std::span<const uint8_t> key, std::span<const uint8_t> payload) const {
    const fs::path path = entry_path(key);
    ByteWriter full_key;
    full_key.put_vector(std::span<const uint8_t>(code_version_));
    full_key.put_bytes(key.data(), key.size());
    const std::vector<uint8_t>& k = full_key.bytes();
    Header h;
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.format_version = kFormatVersion;
    h.header_size = sizeof h;
    h.key_length = k.size();
    h.payload_length = payload.size();
    h.checksum = checksum_of(k, payload);
    const auto fail = [&](const std::string& why) {
        if (!write_failed_.exchange(true)) say("bake cache: cannot save entry '" + path.string() + "' (" + why + "); going on without saving");
    };
    std::error_code ec;
    if (fs::exists(path, ec) && !is_entry(path)) return fail("a file that is not a bake cache entry has its name; left alone");
    const fs::path temp = dir_ / temporary_name(path);
    const std::span<const uint8_t> parts[3] = {{reinterpret_cast<const uint8_t*>(&h), sizeof h}, k, payload};
    std::string why;
    if (!write_new_file(temp, parts, why)) {
        fs::remove(temp, ec);
        return fail(why);
    }
    fs::rename(temp, path, ec);  // POSIX rename: atomic replacement within the directory
    if (ec) {
        fs::remove(temp, ec);
        return fail(ec.message());
    }
    writes_.fetch_add(1);
    // Over the limit as this process last counted the store plus what it has written since: count again.
    const uint64_t written = sizeof h + k.size() + payload.size();
    if (max_bytes_ != 0 && known_bytes_.fetch_add(written) + written > max_bytes_) (void)trim();
}

BlobStoreCounts BlobStore::counts() const { return {hits_.load(), misses_.load(), rejected_.load(), writes_.load(), evicted_.load()}; }

std::optional<fs::path> default_cache_directory() {
    const auto env = [](const char* name) -> std::string {
        const char* v = std::getenv(name);
        return v ? std::string(v) : std::string();
    };
    if (const std::string d = env("ALOHA_CACHE_DIR"); !d.empty()) return fs::path(d);
    if (const std::string x = env("XDG_CACHE_HOME"); !x.empty() && fs::path(x).is_absolute()) return fs::path(x) / "aloha";
    if (const std::string home = env("HOME"); !home.empty()) return fs::path(home) / ".cache" / "aloha";
    return std::nullopt;
}

}  // namespace aloha
