// Test helper: RGBA8 pixels encoded as PNG file bytes in memory (stb_image_write, Debian libstb-dev;
// link aloha_stb), for glTF fixtures that embed their images.
#pragma once

#include <stb_image_write.h>

#include <cstdint>
#include <vector>

namespace aloha::test {

/// PNG bytes of `rgba` (w x h pixels, rows top to bottom, 4 bytes each).
inline std::vector<unsigned char> png_bytes(const std::vector<uint8_t>& rgba, int w, int h) {
    std::vector<unsigned char> out;
    stbi_write_png_to_func([](void* ctx, void* data, int size) {
        auto* o = static_cast<std::vector<unsigned char>*>(ctx);
        o->insert(o->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    }, &out, w, h, 4, rgba.data(), w * 4);
    return out;
}

}  // namespace aloha::test
