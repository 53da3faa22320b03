// BlobStore: round trip, entries another code version or format cannot read, truncated, corrupt and
// foreign files rejected (one message naming the file) and rebuilt, unusable directories; the size limit
// (least recently used entries removed, foreign files and the newest entry kept); ByteReader's bounds;
// build-id reading.
#include "engine/core/blob_store.hpp"
#include "engine/core/build_id.hpp"
#include "engine/core/byte_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>

namespace aloha {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test (removed at the end), and the messages the store gave.
struct StoreFixture : ::testing::Test {
    fs::path dir;
    std::vector<std::string> messages;
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("aloha_blob_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::shared_ptr<BlobStore> open(std::vector<uint8_t> version = {1, 2, 3}, uint64_t max_bytes = BlobStore::kDefaultMaxBytes) {
        return BlobStore::open(dir, std::move(version), [this](const std::string& m) { messages.push_back(m); }, max_bytes);
    }
};

std::vector<uint8_t> bytes_of(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

std::vector<uint8_t> file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& p, const std::vector<uint8_t>& b) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

TEST_F(StoreFixture, RoundTripAcrossStoresOverTheSameDirectory) {
    auto store = open();
    ASSERT_TRUE(store);  // the directory did not exist: made on demand
    const auto key = bytes_of("skin 8x6"), payload = bytes_of("rest positions and indices");
    EXPECT_FALSE(store->get(key));
    store->put(key, payload);
    EXPECT_EQ(store->get(key), payload);
    auto again = open();  // another process's view: the same directory and code version
    EXPECT_EQ(again->get(key), payload);
    EXPECT_FALSE(again->get(bytes_of("skin 16x12")));
    const BlobStoreCounts c = store->counts();
    EXPECT_EQ(c.hits, 1u);
    EXPECT_EQ(c.misses, 1u);
    EXPECT_EQ(c.writes, 1u);
    EXPECT_TRUE(messages.empty());
    // Only the entry is left in the directory (no temporary or probe files).
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
    EXPECT_EQ(files, 1u);
}

TEST_F(StoreFixture, AnotherCodeVersionNeverSeesTheEntry) {
    const auto key = bytes_of("k");
    open({1})->put(key, bytes_of("made by code 1"));
    EXPECT_FALSE(open({2})->get(key));
    EXPECT_TRUE(messages.empty());  // a different name, not a rejected entry
}

// Damages the entry of `key` with `damage`, then expects one rejection message naming the file
// containing `why`, and a rebuild (put) that reads back.
void expect_rejected_then_rebuilt(StoreFixture& f, const std::function<void(std::vector<uint8_t>&)>& damage, const std::string& why) {
    auto store = f.open();
    const auto key = bytes_of("key"), payload = bytes_of("a payload of some length");
    store->put(key, payload);
    const fs::path p = store->entry_path(key);
    std::vector<uint8_t> b = file_bytes(p);
    damage(b);
    write_bytes(p, b);
    EXPECT_FALSE(store->get(key));
    ASSERT_EQ(f.messages.size(), 1u);
    EXPECT_NE(f.messages[0].find(p.string()), std::string::npos) << f.messages[0];
    EXPECT_NE(f.messages[0].find(why), std::string::npos) << f.messages[0];
    EXPECT_EQ(store->counts().rejected, 1u);
    store->put(key, payload);
    EXPECT_EQ(store->get(key), payload);
}

TEST_F(StoreFixture, TruncatedEntryIsRejectedAndRebuilt) {
    // The entry is longer than its header (the size check keeps GCC's -O1 sanitizer build from seeing a wrapped size).
    expect_rejected_then_rebuilt(*this, [](std::vector<uint8_t>& b) { if (b.size() > 5) b.resize(b.size() - 5); }, "truncated");
}

TEST_F(StoreFixture, EntryShorterThanItsHeaderIsRejectedAndRebuilt) {
    expect_rejected_then_rebuilt(*this, [](std::vector<uint8_t>& b) { b.resize(12); }, "truncated");
}

TEST_F(StoreFixture, CorruptPayloadIsRejectedAndRebuilt) {
    expect_rejected_then_rebuilt(*this, [](std::vector<uint8_t>& b) { b.back() ^= 0x10; }, "corrupt");
}

TEST_F(StoreFixture, OtherFormatVersionIsRejectedAndRebuilt) {
    // The format version is the 32-bit word after the 8-byte magic.
    expect_rejected_then_rebuilt(*this, [](std::vector<uint8_t>& b) { b[8] = static_cast<uint8_t>(BlobStore::kFormatVersion + 1); },
                                 "format version");
}

TEST_F(StoreFixture, AFileThatIsNotAnEntryIsNeverOverwritten) {
    auto store = open();
    const auto key = bytes_of("key");
    const fs::path p = store->entry_path(key);
    const auto foreign = bytes_of("somebody's notes");
    write_bytes(p, foreign);
    EXPECT_FALSE(store->get(key));  // rejected: wrong magic
    store->put(key, bytes_of("payload"));
    EXPECT_EQ(file_bytes(p), foreign);
    ASSERT_EQ(messages.size(), 2u);
    EXPECT_NE(messages[1].find("not a bake cache entry"), std::string::npos) << messages[1];
}

TEST_F(StoreFixture, DirectoryThatCannotBeMadeMeansNoStoreWithOneMessage) {
    // A directory below a regular file cannot be made, whoever runs the test (root included).
    fs::create_directories(dir);
    write_bytes(dir / "file", bytes_of("x"));
    std::vector<std::string> said;
    auto store = BlobStore::open(dir / "file" / "cache", {1}, [&](const std::string& m) { said.push_back(m); });
    EXPECT_FALSE(store);
    ASSERT_EQ(said.size(), 1u);
    EXPECT_NE(said[0].find((dir / "file" / "cache").string()), std::string::npos) << said[0];
}

// Entries "e0".."e{n-1}" of `payload_bytes` each, e0 used longest ago (modification times an hour apart,
// the last an hour ago); returns their file sizes.
std::vector<uint64_t> put_aged(BlobStore& store, size_t n, size_t payload_bytes) {
    std::vector<uint64_t> sizes;
    const auto now = fs::file_time_type::clock::now();
    for (size_t i = 0; i < n; ++i) {
        const auto key = bytes_of("e" + std::to_string(i));
        store.put(key, std::vector<uint8_t>(payload_bytes, static_cast<uint8_t>(i)));
        fs::last_write_time(store.entry_path(key), now - std::chrono::hours(n - i));
        sizes.push_back(fs::file_size(store.entry_path(key)));
    }
    return sizes;
}

TEST_F(StoreFixture, OpeningOverTheLimitRemovesTheEntriesUsedLongestAgo) {
    auto unlimited = open({1, 2, 3}, 0);
    const std::vector<uint64_t> sizes = put_aged(*unlimited, 4, 1000);
    EXPECT_EQ(unlimited->counts().evicted, 0u);
    // Room for two and a half entries: e0 and e1 go, e2 and e3 stay.
    auto limited = open({1, 2, 3}, sizes[0] * 5 / 2);
    EXPECT_EQ(limited->counts().evicted, 2u);
    for (size_t i = 0; i < 4; ++i) EXPECT_EQ(limited->get(bytes_of("e" + std::to_string(i))).has_value(), i >= 2) << i;
    const BlobStoreTrim again = limited->trim();
    EXPECT_EQ(again.entries, 2u);
    EXPECT_EQ(again.bytes, sizes[2] + sizes[3]);
    EXPECT_EQ(again.removed, 0u);
}

TEST_F(StoreFixture, AHitMakesAnEntryTheMostRecentlyUsed) {
    auto unlimited = open({1, 2, 3}, 0);
    const std::vector<uint64_t> sizes = put_aged(*unlimited, 3, 1000);
    ASSERT_TRUE(unlimited->get(bytes_of("e0")));  // the oldest, used now
    // A put over a limit of two entries trims: e1 is now the one used longest ago.
    auto limited = open({1, 2, 3}, sizes[0] * 3);
    limited->put(bytes_of("e3"), std::vector<uint8_t>(1000, 3));
    EXPECT_EQ(limited->counts().evicted, 1u);
    EXPECT_FALSE(limited->get(bytes_of("e1")));
    for (const char* kept : {"e0", "e2", "e3"}) EXPECT_TRUE(limited->get(bytes_of(kept))) << kept;
}

TEST_F(StoreFixture, TheLimitNeverRemovesForeignFilesOrTheNewestEntry) {
    auto unlimited = open({1, 2, 3}, 0);
    put_aged(*unlimited, 3, 1000);
    // A foreign file under an entry's name, one under another name, a temporary file a crashed write left
    // two hours ago and one being written now.
    const fs::path foreign_entry = unlimited->entry_path(bytes_of("foreign"));
    write_bytes(foreign_entry, std::vector<uint8_t>(5000, 7));
    fs::last_write_time(foreign_entry, fs::file_time_type::clock::now() - std::chrono::hours(10));
    write_bytes(dir / "notes.txt", std::vector<uint8_t>(5000, 8));
    const fs::path stale = dir / (foreign_entry.filename().string() + ".tmp.1.0"), fresh = dir / (foreign_entry.filename().string() + ".tmp.2.0");
    write_bytes(stale, bytes_of("half"));
    fs::last_write_time(stale, fs::file_time_type::clock::now() - std::chrono::hours(2));
    write_bytes(fresh, bytes_of("half"));
    auto tiny = open({1, 2, 3}, 1);  // one byte: everything that may go, goes
    const BlobStoreTrim t = tiny->trim();
    EXPECT_EQ(tiny->counts().evicted, 2u);  // e0 and e1 when opened; the foreign file is not an entry
    EXPECT_TRUE(fs::exists(foreign_entry));
    EXPECT_TRUE(fs::exists(dir / "notes.txt"));
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(fresh));
    EXPECT_TRUE(tiny->get(bytes_of("e2")));  // the newest entry stays, whatever the limit
    EXPECT_EQ(t.removed, 0u);
}

TEST(CacheLimit, ParsesWholeMebibytesAndNamesABadEnvironmentValue) {
    EXPECT_EQ(parse_cache_limit_mib("0"), 0u);
    EXPECT_EQ(parse_cache_limit_mib("512"), uint64_t{512} << 20);
    for (const char* bad : {"", "-1", "1.5", "12MB", "1099511627777", "99999999999999"}) EXPECT_FALSE(parse_cache_limit_mib(bad)) << bad;
    std::vector<std::string> said;
    const auto log = [&](const std::string& m) { said.push_back(m); };
    ::setenv("ALOHA_CACHE_MAX_MB", "lots", 1);
    EXPECT_EQ(default_cache_limit_bytes(log), BlobStore::kDefaultMaxBytes);
    ASSERT_EQ(said.size(), 1u);
    EXPECT_NE(said[0].find("ALOHA_CACHE_MAX_MB='lots'"), std::string::npos) << said[0];
    ::setenv("ALOHA_CACHE_MAX_MB", "64", 1);
    EXPECT_EQ(default_cache_limit_bytes(log), uint64_t{64} << 20);
    ::unsetenv("ALOHA_CACHE_MAX_MB");
    EXPECT_EQ(default_cache_limit_bytes(log), BlobStore::kDefaultMaxBytes);
    EXPECT_EQ(said.size(), 1u);
}

TEST(ByteReader, ReadsBackWhatWasWrittenAndStopsAtTheEnd) {
    ByteWriter w;
    w.put<uint32_t>(7);
    w.put_vector(std::vector<float>{1.5f, -2.0f});
    w.put_string("abc");
    const std::vector<uint8_t> bytes = w.take();
    ByteReader r(bytes);
    uint32_t u = 0;
    std::vector<float> v;
    std::string s;
    EXPECT_TRUE(r.get(u) && r.get_vector(v) && r.get_string(s));
    EXPECT_TRUE(r.done());
    EXPECT_EQ(u, 7u);
    EXPECT_EQ(v, (std::vector<float>{1.5f, -2.0f}));
    EXPECT_EQ(s, "abc");
    // Cut short: the vector's count says more than is left, the reader fails and stays failed.
    ByteReader cut(std::span<const uint8_t>(bytes).first(bytes.size() - 6));
    EXPECT_TRUE(cut.get(u));
    EXPECT_FALSE(cut.get_vector(v) && cut.get_string(s));
    EXPECT_FALSE(cut.ok());
    EXPECT_FALSE(cut.get(u));
}

// A content-addressed key: the kind and a digest of the inputs, the same size whatever they hold.
TEST(DigestKey, SameInputsSameKeyAndEveryByteCounts) {
    std::vector<uint8_t> inputs(100000);
    for (size_t i = 0; i < inputs.size(); ++i) inputs[i] = static_cast<uint8_t>(i * 31);
    const std::vector<uint8_t> key = digest_key(7, inputs);
    EXPECT_EQ(key.size(), 28u);
    EXPECT_EQ(digest_key(7, inputs), key);
    EXPECT_NE(digest_key(8, inputs), key);
    for (const size_t at : {size_t{0}, size_t{4095}, inputs.size() - 1}) {
        std::vector<uint8_t> changed = inputs;
        changed[at] ^= 1;
        EXPECT_NE(digest_key(7, changed), key) << "byte " << at;
    }
    EXPECT_NE(digest_key(7, std::span(inputs).first(inputs.size() - 1)), key);
}

TEST(BuildId, TheTestProgramHasOne) {
    // Debian's toolchain links with --build-id (sha1: 20 bytes).
    auto id = build_id_of(reinterpret_cast<uintptr_t>(&hash_bytes64));
    ASSERT_TRUE(id.ok()) << id.error().to_string();
    EXPECT_EQ(id.value().id.size(), 20u);
    auto both = build_ids_of(std::vector<uintptr_t>{reinterpret_cast<uintptr_t>(&hash_bytes64),
                                                    reinterpret_cast<uintptr_t>(&build_ids_of)});
    ASSERT_TRUE(both.ok());
    EXPECT_EQ(both.value().size(), 21u);  // one object: its id once, after its length
    EXPECT_FALSE(build_id_of(0).ok());
}

}  // namespace
}  // namespace aloha
