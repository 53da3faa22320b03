// The GNU build-id of loaded code: what identifies the exact machine code a process runs, for caches
// whose entries that code produced (the bake cache's code version).
#pragma once

#include "engine/core/result.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// The build-id note (NT_GNU_BUILD_ID in a PT_NOTE segment) of the loaded object (executable or
/// shared library) whose segments contain `address`, and the object's name ("" for the executable).
struct LoadedBuildId {
    std::string object;          ///< the object's path as the dynamic loader names it ("" = the executable)
    std::vector<uint8_t> id;     ///< the note's descriptor bytes (20 for the linker's default sha1)
};

/// Finds the object containing `address` (dl_iterate_phdr over the loaded objects) and reads its
/// build-id. Errors: no loaded object contains the address, or the object has no build-id note (a link
/// without --build-id): the message names the object.
[[nodiscard]] Result<LoadedBuildId> build_id_of(uintptr_t address);

/// The build-ids of the distinct objects containing `addresses`, concatenated in first-seen order with
/// each id's length before it. Errors as build_id_of, for the first address that fails.
[[nodiscard]] Result<std::vector<uint8_t>> build_ids_of(std::span<const uintptr_t> addresses);

}  // namespace aloha
