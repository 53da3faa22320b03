// A small content-addressed store of derived data on disk (the idea of Unreal's derived-data cache):
// the value for a key is bytes some deterministic code computed from the key's inputs, saved so the
// next process finds them instead of computing them again.
//
// An entry's name is a 128-bit digest of (code version, key); the file holds a header (magic, format
// version, key and payload lengths, a checksum over key and payload), the key itself (compared on
// read, so a digest collision is a miss, never wrong data) and the payload. Writes go to a temporary
// file in the same directory, then rename over the entry: a reader (another process, ctest -j2) sees
// the old entry, the new one or none, never part of one. A truncated, corrupt or foreign entry is a
// miss with one message naming the file; the caller rebuilds and put() replaces it. A directory that
// cannot be made or written means no store (open() says why once); the store never replaces a file
// that is not one of its entries.
//
// The store keeps itself under a size limit (least recently used first): a hit refreshes its entry's
// modification time, and open() and a put() that may take the store over it remove the entries used
// longest ago while the entries together are over the limit (never the newest one), along with
// temporary files a crashed writer left over an hour ago. Entries are recognised by name and magic;
// nothing else in the directory is touched.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Where the store's messages go (one line each, no newline); empty: standard error.
using BlobStoreLog = std::function<void(const std::string&)>;

/// What the store did since it was opened (for reports and tests).
struct BlobStoreCounts {
    uint64_t hits = 0;      ///< get() found a valid entry
    uint64_t misses = 0;    ///< get() found no entry
    uint64_t rejected = 0;  ///< get() found an entry it could not use (truncated, corrupt, other version or key)
    uint64_t writes = 0;    ///< put() saved an entry
    uint64_t evicted = 0;   ///< entries removed to keep the store under its size limit
};

/// What one trim() found and did.
struct BlobStoreTrim {
    uint64_t entries = 0;          ///< entries left
    uint64_t bytes = 0;            ///< their bytes
    uint64_t removed = 0;          ///< entries removed (least recently used first)
    uint64_t removed_bytes = 0;    ///< their bytes
    uint64_t stale_temporaries = 0;  ///< temporary files of writes that never finished, removed
};

/// The content-addressed store over one directory. Thread-safe: get() and put() may run concurrently
/// from several threads and processes.
class BlobStore {
public:
    /// The header's first bytes.
    static constexpr char kMagic[8] = {'A', 'L', 'O', 'H', 'A', 'B', 'A', 'K'};
    /// The entry layout this code reads and writes.
    static constexpr uint32_t kFormatVersion = 1;
    /// The size limit when none is given: 1 GiB.
    static constexpr uint64_t kDefaultMaxBytes = uint64_t{1} << 30;

    /// Opens the store over `dir` (created, with its parents, when missing), for entries made by code
    /// `code_version` (bytes that change whenever that code changes), holding its entries to `max_bytes`
    /// together (0: no limit) and trimming it to that at once. Returns nullptr, after one message naming
    /// the directory and the reason, when the directory cannot be made or written.
    static std::shared_ptr<BlobStore> open(const std::filesystem::path& dir, std::vector<uint8_t> code_version,
                                           BlobStoreLog log = {}, uint64_t max_bytes = kDefaultMaxBytes);

    /// The payload saved for `key`, or nothing (no entry, or one rejected with a message).
    [[nodiscard]] std::optional<std::vector<uint8_t>> get(std::span<const uint8_t> key) const;
    /// Saves `payload` for `key` (atomically replacing an entry of the store), then trims the store to its
    /// limit when the entries' bytes at the last trim plus this process's writes since exceed it (a
    /// replaced entry counts twice until then; other processes' writes are counted at the next trim). A failed write gives one message for the store's life and is otherwise ignored (the store
    /// is a cache).
    void put(std::span<const uint8_t> key, std::span<const uint8_t> payload) const;
    /// Removes entries, least recently used first (by modification time), while the entries are over the
    /// size limit, never the most recent one; and temporary files older than an hour. Entries other
    /// processes hold open stay readable to them (POSIX). Thread-safe; errors only skip files.
    BlobStoreTrim trim() const;
    /// True when the file at `path` starts with the store's magic (one of its entries, whatever its state).
    [[nodiscard]] static bool is_entry(const std::filesystem::path& path);
    /// The size limit (0: none).
    [[nodiscard]] uint64_t max_bytes() const { return max_bytes_; }

    /// The file an entry for `key` lives in.
    [[nodiscard]] std::filesystem::path entry_path(std::span<const uint8_t> key) const;
    /// The store's directory.
    [[nodiscard]] const std::filesystem::path& directory() const { return dir_; }
    /// The code version the store's entries are read and written for (open()'s `code_version`).
    [[nodiscard]] std::span<const uint8_t> code_version() const { return code_version_; }
    /// Counts of hits, misses, rejections and writes so far.
    [[nodiscard]] BlobStoreCounts counts() const;

private:
    BlobStore() = default;
    void say(const std::string& message) const;
    std::filesystem::path dir_;
    std::vector<uint8_t> code_version_;
    BlobStoreLog log_;
    uint64_t max_bytes_ = kDefaultMaxBytes;
    mutable std::atomic<uint64_t> hits_{0}, misses_{0}, rejected_{0}, writes_{0}, evicted_{0};
    mutable std::atomic<uint64_t> known_bytes_{0};  ///< the entries' bytes at the last trim() plus this process's writes since
    mutable std::atomic<bool> write_failed_{false};
    mutable std::mutex trim_mutex_;  ///< one trim at a time in this process (two would remove more than needed)
};

/// The default store directory: $ALOHA_CACHE_DIR when set and not empty, else $XDG_CACHE_HOME/aloha
/// (an absolute XDG_CACHE_HOME), else $HOME/.cache/aloha; nothing when none of these is set.
[[nodiscard]] std::optional<std::filesystem::path> default_cache_directory();

/// The size limit named by `text` (a whole number of MiB, 0 = no limit, at most 2^40), or nothing when it
/// is not one.
[[nodiscard]] std::optional<uint64_t> parse_cache_limit_mib(const std::string& text);

/// The default size limit: $ALOHA_CACHE_MAX_MB (MiB, 0 = no limit) when set and not empty, else
/// BlobStore::kDefaultMaxBytes. A value that is not a whole number of MiB gives one message naming the
/// variable and its value, and the default.
[[nodiscard]] uint64_t default_cache_limit_bytes(const BlobStoreLog& log = {});

}  // namespace aloha
