#include "engine/assets/file_io.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

namespace aloha {

namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

// Reads `path` into `out` (a std::string or std::vector<unsigned char>), refusing files over `max_bytes`.
template <class Buffer>
Result<Buffer> read_file(const std::string& path, size_t max_bytes) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(st)) {
        return make_error(ErrorKind::Io, path, "file not found", ec ? ec.value() : ENOENT);
    }
    if (!std::filesystem::is_regular_file(st)) return make_error(ErrorKind::Io, path, "not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) {
        return make_error(ErrorKind::Io, path, "cannot read the file size: " + ec.message(), ec.value());
    }
    if (size > max_bytes)
        return make_error(path, "file is " + std::to_string(size) + " bytes; the limit is " +
                                    std::to_string(max_bytes) + " bytes");
    std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
    if (!f) {
        const int err = errno;
        return make_error(ErrorKind::Io, path, std::string("cannot open: ") + std::strerror(err), err);
    }
    Buffer data;
    data.resize(static_cast<size_t>(size));
    const size_t got = size == 0 ? 0 : std::fread(data.data(), 1, data.size(), f.get());
    if (got != data.size()) {
        const int err = std::ferror(f.get()) ? errno : 0;
        return make_error(ErrorKind::Io, path, "read " + std::to_string(got) + " of " + std::to_string(size) +
                                                   " bytes" + (err != 0 ? std::string(": ") + std::strerror(err) : ""), err);
    }
    // A file that grew since we asked for its size is read only up to that size: check for more.
    if (std::fgetc(f.get()) != EOF) return make_error(ErrorKind::Io, path, "file changed size while being read");
    return data;
}

}  // namespace

Result<std::string> read_text_file(const std::string& path, size_t max_bytes) {
    return read_file<std::string>(path, max_bytes);
}

Result<std::vector<unsigned char>> read_binary_file(const std::string& path, size_t max_bytes) {
    return read_file<std::vector<unsigned char>>(path, max_bytes);
}

}  // namespace aloha
