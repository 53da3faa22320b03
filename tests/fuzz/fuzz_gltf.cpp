// libFuzzer target: glTF characters (parse_gltf_character): JSON .gltf text or binary .glb bytes
// (the loader decides by the "glTF" magic). base_dir is an empty folder so external buffer URIs
// resolve to nothing.
#include "engine/assets/gltf_loader.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string kBaseDir = std::string(ALOHA_FUZZ_EMPTY_DIR);
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    aloha::Result<aloha::GltfCharacter> c = aloha::parse_gltf_character(bytes, "fuzz.glb", kBaseDir);
    if (!c.ok()) {
        if (c.error().file.empty()) __builtin_trap();  // every error must name the file
        return 0;
    }
    // Documented postconditions of a loaded character.
    const aloha::GltfCharacter& ch = c.value();
    if (ch.inverse_bind_matrices.size() != ch.skeleton.joints.size()) __builtin_trap();
    for (const aloha::GltfSkinnedMesh& m : ch.meshes) {
        if (m.normals.size() != m.positions.size() || m.joints.size() != m.positions.size() ||
            m.weights.size() != m.positions.size())
            __builtin_trap();
        for (uint32_t i : m.indices)
            if (i >= m.positions.size()) __builtin_trap();
        for (const auto& j : m.joints)
            for (int k = 0; k < 4; ++k)
                if (j[k] >= ch.skeleton.joints.size()) __builtin_trap();
    }
    return 0;
}
