// glTF image decoding for the character loader (tinygltf's image callback): PNG and JPEG with stb_image,
// WebP (EXT_texture_webp) with libwebp, each into RGBA8, refusing images over 8192 pixels a side. A failure
// is logged and the load goes on: the materials using the image are drawn without it. Images in
// bufferViews are decoded after the load, once their view is checked against its buffer.
#include "engine/assets/gltf_detail.hpp"

#include <stb_image.h>
#include <webp/decode.h>

#include <algorithm>
#include <limits>
#include <string>

namespace aloha::gltf_detail {

namespace {

constexpr int kMaxImageSide = 8192;

// Whether a w x h image may be decoded (each side 1..kMaxImageSide); when not, the reason goes to `log`.
bool image_size_ok(int w, int h, int index, ImageDecodeLog* log) {
    if (w > 0 && h > 0 && w <= kMaxImageSide && h <= kMaxImageSide) return true;
    log->failures.emplace_back(index, std::to_string(w) + " x " + std::to_string(h) + " pixels exceeds the limit of " + std::to_string(kMaxImageSide) +
                                          " x " + std::to_string(kMaxImageSide));
    return false;
}

// True when `bytes` hold a WebP file (a RIFF container of form type WEBP).
bool is_webp(const unsigned char* bytes, int size) {
    return size >= 12 && std::equal(bytes, bytes + 4, "RIFF") && std::equal(bytes + 8, bytes + 12, "WEBP");
}

// Decodes a WebP image with libwebp into `image` (RGBA8); when it cannot, `image` stays empty and `log` says why.
void decode_webp(tinygltf::Image* image, int index, const unsigned char* bytes, int size, ImageDecodeLog* log) {
    int w = 0, h = 0;
    if (!WebPGetInfo(bytes, static_cast<size_t>(size), &w, &h)) {
        log->failures.emplace_back(index, "not a WebP image libwebp can read (bad header)");
        return;
    }
    if (!image_size_ok(w, h, index, log)) return;
    image->image.resize(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
    if (!WebPDecodeRGBAInto(bytes, static_cast<size_t>(size), image->image.data(), image->image.size(), w * 4)) {
        image->image.clear();
        log->failures.emplace_back(index, "WebP decoding failed (corrupt data)");
        return;
    }
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
}

// Decodes `size` bytes known to be readable into `image` (RGBA8), or logs why not.
void decode_bytes(tinygltf::Image* image, int index, const unsigned char* bytes, int size, ImageDecodeLog* log) {
    if (is_webp(bytes, size)) {
        decode_webp(image, index, bytes, size, log);
        return;
    }
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) {
        log->failures.emplace_back(index, std::string("not a PNG, JPEG or WebP image (") + stbi_failure_reason() + ")");
        return;
    }
    if (!image_size_ok(w, h, index, log)) return;
    unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &comp, 4);
    if (!pixels) {
        log->failures.emplace_back(index, std::string("decoding failed (") + stbi_failure_reason() + ")");
        return;
    }
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels, pixels + static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
    stbi_image_free(pixels);
}

}  // namespace

bool decode_image(tinygltf::Image* image, int index, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void* user) {
    // A bufferView's bytes are not checked against the buffer by tinygltf: decoded later, checked.
    if (image->bufferView >= 0) return true;
    decode_bytes(image, index, bytes, size, static_cast<ImageDecodeLog*>(user));
    return true;  // a failure is noted; the materials using the image are drawn untextured
}

void decode_buffer_view_images(tinygltf::Model* model, ImageDecodeLog* log) {
    for (size_t i = 0; i < model->images.size(); ++i) {
        tinygltf::Image& image = model->images[i];
        if (image.bufferView < 0) continue;
        const int index = static_cast<int>(i);
        // tinygltf checked the view and buffer indices before calling decode_image.
        const tinygltf::BufferView& view = model->bufferViews[static_cast<size_t>(image.bufferView)];
        const std::vector<unsigned char>& data = model->buffers[static_cast<size_t>(view.buffer)].data;
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
            log->failures.emplace_back(index, "bufferView " + std::to_string(image.bufferView) + " (bytes " + std::to_string(view.byteOffset) +
                                                  " to " + std::to_string(view.byteOffset + view.byteLength) + ") lies outside buffer " +
                                                  std::to_string(view.buffer) + " of " + std::to_string(data.size()) + " bytes");
            continue;
        }
        if (view.byteLength > static_cast<size_t>(std::numeric_limits<int>::max())) {
            log->failures.emplace_back(index, "bufferView " + std::to_string(image.bufferView) + " is too large for an image (" +
                                                  std::to_string(view.byteLength) + " bytes)");
            continue;
        }
        decode_bytes(&image, index, data.data() + view.byteOffset, static_cast<int>(view.byteLength), log);
    }
    // Notes in image order, whichever way each image was stored.
    std::stable_sort(log->failures.begin(), log->failures.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
}

}  // namespace aloha::gltf_detail
