// libFuzzer target: scene files (parse_scene). The scene is anchored in the repository's data/scenes
// folder so builtin: names and relative paths resolve against real files, as they would for a user.
#include "host/scene/scene_loader.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string kFile = std::string(ALOHA_SOURCE_DIR) + "/data/scenes/fuzz_input.json";
    const std::string text(reinterpret_cast<const char*>(data), size);
    aloha::Result<aloha::SceneDesc> scene = aloha::parse_scene(text, kFile);
    if (!scene.ok() && scene.error().file.empty()) __builtin_trap();  // every error must name the file
    return 0;
}
