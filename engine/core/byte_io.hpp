// Plain little-endian binary writing and reading of trivially copyable values and vectors of them
// (glm vectors, indices, weights), for the bake cache's entries and their key material. The bytes are
// the values' object representation: ALOHA builds for little-endian targets only (static_assert
// below), and every type written is a fixed-size aggregate of 8/16/32/64-bit integers and IEEE
// floats, so the bytes are the little-endian encoding and reading them back gives the same bits.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace aloha {

static_assert(std::endian::native == std::endian::little, "byte_io writes the native representation as little-endian");

/// Appends values to a byte vector.
class ByteWriter {
public:
    /// Appends the bytes of one trivially copyable value.
    template <class T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        put_bytes(&value, sizeof(T));
    }
    /// Appends a 64-bit element count, then the elements' bytes.
    template <class T>
    void put_vector(std::span<const T> values) {
        static_assert(std::is_trivially_copyable_v<T>);
        put(static_cast<uint64_t>(values.size()));
        put_bytes(values.data(), values.size_bytes());
    }
    /// put_vector of a std::vector.
    template <class T>
    void put_vector(const std::vector<T>& values) { put_vector(std::span<const T>(values)); }
    /// Appends a 64-bit length, then the characters.
    void put_string(std::string_view s) {
        put(static_cast<uint64_t>(s.size()));
        put_bytes(s.data(), s.size());
    }
    /// Appends `size` raw bytes.
    void put_bytes(const void* data, size_t size) {
        const auto* p = static_cast<const uint8_t*>(data);
        bytes_.insert(bytes_.end(), p, p + size);
    }
    /// The bytes written so far.
    [[nodiscard]] const std::vector<uint8_t>& bytes() const { return bytes_; }
    /// Moves the bytes out (the writer is left empty).
    [[nodiscard]] std::vector<uint8_t> take() { return std::move(bytes_); }

private:
    std::vector<uint8_t> bytes_;
};

/// Reads values back in the order a ByteWriter wrote them. Every read checks the bytes left: a short
/// or inconsistent input makes the reader fail (ok() false) and the reads after it return nothing,
/// never read past the end.
class ByteReader {
public:
    /// Reads from `bytes` (which must outlive the reader).
    explicit ByteReader(std::span<const uint8_t> bytes) : bytes_(bytes) {}

    /// Reads one value; false (and the reader fails) when too few bytes are left.
    template <class T>
    bool get(T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        return get_bytes(&value, sizeof(T));
    }
    /// Reads a vector written by put_vector; fails when its count exceeds the bytes left.
    template <class T>
    bool get_vector(std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        uint64_t n = 0;
        if (!get(n) || n > left() / sizeof(T)) return fail();
        values.resize(static_cast<size_t>(n));
        return get_bytes(values.data(), static_cast<size_t>(n) * sizeof(T));
    }
    /// Reads a string written by put_string.
    bool get_string(std::string& s) {
        uint64_t n = 0;
        if (!get(n) || n > left()) return fail();
        s.assign(reinterpret_cast<const char*>(bytes_.data() + pos_), static_cast<size_t>(n));
        pos_ += static_cast<size_t>(n);
        return true;
    }
    /// Copies `size` raw bytes; false (and the reader fails) when fewer are left.
    bool get_bytes(void* out, size_t size) {
        if (!ok_ || size > left()) return fail();
        if (size > 0) std::memcpy(out, bytes_.data() + pos_, size);
        pos_ += size;
        return true;
    }
    /// Bytes not read yet.
    [[nodiscard]] size_t left() const { return bytes_.size() - pos_; }
    /// True while every read so far succeeded.
    [[nodiscard]] bool ok() const { return ok_; }
    /// True when every read succeeded and every byte was read (a complete, exact payload).
    [[nodiscard]] bool done() const { return ok_ && left() == 0; }

private:
    bool fail() {
        ok_ = false;
        return false;
    }
    std::span<const uint8_t> bytes_;
    size_t pos_ = 0;
    bool ok_ = true;
};

/// A 64-bit hash of `bytes` (8 bytes per step, a multiply-xorshift mix per word, the length and
/// `seed` mixed in): a checksum and a key digest, not a cryptographic hash. Same bytes, same value,
/// on every run.
[[nodiscard]] uint64_t hash_bytes64(std::span<const uint8_t> bytes, uint64_t seed = 0);

/// A content-addressed store key: `kind`, then a 128-bit digest of `inputs` (two independently seeded
/// hash_bytes64) and their length, 28 bytes whatever the inputs' size (a store keeps each key beside its payload,
/// and the inputs, a refined surface or an atlas's meshes and textures, can be megabytes).
[[nodiscard]] std::vector<uint8_t> digest_key(uint32_t kind, std::span<const uint8_t> inputs);

}  // namespace aloha
