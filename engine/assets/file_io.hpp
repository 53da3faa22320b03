// Reading whole asset files into memory with bounded size and errors that name the file.
#pragma once

#include "engine/core/result.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace aloha {

/// Largest file the asset loaders read (256 MiB); bigger files are refused before allocating.
inline constexpr size_t kMaxAssetFileBytes = size_t{256} << 20;

/// Reads the whole file at `path` as text. Errors: missing, not a regular file, unreadable, larger
/// than `max_bytes`. The Error's `file` is `path` and `code` the errno where one applies.
Result<std::string> read_text_file(const std::string& path, size_t max_bytes = kMaxAssetFileBytes);

/// Reads the whole file at `path` as bytes, with the same checks and errors as read_text_file().
Result<std::vector<unsigned char>> read_binary_file(const std::string& path,
                                                    size_t max_bytes = kMaxAssetFileBytes);

}  // namespace aloha
