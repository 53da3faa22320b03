// The digest of the code that computes the load-time bakes, generated at build time by cmake/BakeCodeDigest.cmake.
#pragma once

namespace aloha {

/// SHA-256 (64 hexadecimal digits) over the library's sources, shaders and CMake settings (relative paths and
/// contents), the compiler, its flags, the configuration and the header libraries' versions: equal in every program
/// built from the same sources the same way, different after any edit of them. Part of skin_bake_code_version().
extern const char kBakeCodeDigest[];

}  // namespace aloha
