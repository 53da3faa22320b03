// glTF materials for the character loader: base colour factor, alpha mode, base colour texture (its
// texCoord set, KHR_texture_transform, sampler wrap and filter modes, EXT_texture_webp's source) and the
// decoding of the images they use (stb_image for PNG and JPEG, libwebp for WebP; RGBA8).
#include "engine/assets/gltf_detail.hpp"

#include <stb_image.h>
#include <webp/decode.h>

#include <algorithm>
#include <cmath>

namespace aloha::gltf_detail {

namespace {

constexpr int kMaxImageSide = 8192;

TextureWrap wrap_of(int gl) {
    switch (gl) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
        default: return TextureWrap::Repeat;
    }
}

// The KHR_texture_transform object `ext` as the matrix translation * rotation * scale of the extension's
// specification (rotation counter-clockwise in UV space); its texCoord, when given, replaces `*texcoord`.
Result<glm::mat3> texture_transform(const tinygltf::Value& ext, const std::string& file, const std::string& where, int* texcoord) {
    auto fail = [&](const std::string& msg) { return make_error(file, msg, 0, 0, where); };
    if (!ext.IsObject()) return fail("is not an object");
    auto pair = [&](const char* key, glm::vec2 fallback) -> Result<glm::vec2> {
        if (!ext.Has(key)) return fallback;
        const tinygltf::Value& v = ext.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
            return fail(std::string("'") + key + "' is not an array of two numbers");
        const glm::vec2 out(static_cast<float>(v.Get(0).GetNumberAsDouble()), static_cast<float>(v.Get(1).GetNumberAsDouble()));
        if (!std::isfinite(out.x) || !std::isfinite(out.y)) return fail(std::string("'") + key + "' is NaN, infinite or out of float range");
        return out;
    };
    Result<glm::vec2> offset = pair("offset", glm::vec2(0.0f));
    if (!offset.ok()) return offset.error();
    Result<glm::vec2> scale = pair("scale", glm::vec2(1.0f));
    if (!scale.ok()) return scale.error();
    float rotation = 0.0f;
    if (ext.Has("rotation")) {
        if (!ext.Get("rotation").IsNumber()) return fail("'rotation' is not a number");
        rotation = static_cast<float>(ext.Get("rotation").GetNumberAsDouble());
        if (!std::isfinite(rotation)) return fail("'rotation' is NaN, infinite or out of float range");
    }
    if (ext.Has("texCoord")) {
        const int64_t t = non_negative_integer(ext.Get("texCoord"));
        if (t < 0 || t > 1000) return fail("'texCoord' is not a non-negative integer up to 1000");
        *texcoord = static_cast<int>(t);
    }
    const float c = std::cos(rotation), s = std::sin(rotation);
    const glm::mat3 translate(1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, offset.value().x, offset.value().y, 1.0f);
    const glm::mat3 rotate(c, s, 0.0f, -s, c, 0.0f, 0.0f, 0.0f, 1.0f);
    const glm::mat3 scaling(scale.value().x, 0.0f, 0.0f, 0.0f, scale.value().y, 0.0f, 0.0f, 0.0f, 1.0f);
    return translate * rotate * scaling;
}

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

// The image a texture draws: its EXT_texture_webp source when it has one (the extension's fallback `source`
// is for readers without WebP), else its `source`; -1 when it has neither. `from_webp` says which. Errors name a
// malformed extension.
Result<int> texture_image(const tinygltf::Texture& tex, const std::string& file, const std::string& where, bool* from_webp) {
    const auto ext = tex.extensions.find(std::string(kWebpExtension));
    *from_webp = ext != tex.extensions.end();
    if (!*from_webp) return tex.source;
    const std::string at = where + ".extensions." + std::string(kWebpExtension) + ".source";
    if (!ext->second.IsObject() || !ext->second.Has("source")) return make_error(file, "has no 'source' image index", 0, 0, at);
    const int64_t source = non_negative_integer(ext->second.Get("source"));
    if (source < 0 || source > INT32_MAX) return make_error(file, "expected an image index", 0, 0, at);
    return static_cast<int>(source);
}

}  // namespace

bool decode_image(tinygltf::Image* image, int index, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void* user) {
    auto* log = static_cast<ImageDecodeLog*>(user);
    if (is_webp(bytes, size)) {
        decode_webp(image, index, bytes, size, log);
        return true;  // a failure is noted; the materials using the image are drawn untextured
    }
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) {
        log->failures.emplace_back(index, std::string("not a PNG, JPEG or WebP image (") + stbi_failure_reason() + ")");
        return true;
    }
    if (!image_size_ok(w, h, index, log)) return true;
    unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &comp, 4);
    if (!pixels) {
        log->failures.emplace_back(index, std::string("decoding failed (") + stbi_failure_reason() + ")");
        return true;
    }
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels, pixels + static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
    stbi_image_free(pixels);
    return true;
}

Status read_materials(const tinygltf::Model& model, const std::string& file, GltfCharacter* out, std::vector<MaterialUv>* uv) {
    std::vector<int> texture_of_image(model.images.size(), -1);  // index into out->textures, -2 = unusable
    uv->assign(model.materials.size(), MaterialUv{});
    size_t transformed = 0, webp = 0, unlit = 0;
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& src = model.materials[i];
        const std::string where = "materials[" + std::to_string(i) + "]";
        SurfaceMaterial m;
        m.name = src.name.empty() ? "material" + std::to_string(i) : src.name;
        m.double_sided = src.doubleSided;
        m.unlit = src.extensions.count("KHR_materials_unlit") > 0;
        unlit += m.unlit ? 1 : 0;
        const std::vector<double>& f = src.pbrMetallicRoughness.baseColorFactor;
        if (f.size() != 4) return make_error(file, "baseColorFactor has " + std::to_string(f.size()) + " values, expected 4", 0, 0, where + ".pbrMetallicRoughness");
        for (int c = 0; c < 4; ++c) {
            if (!std::isfinite(f[static_cast<size_t>(c)]) || f[static_cast<size_t>(c)] < 0.0 || f[static_cast<size_t>(c)] > 1.0)
                return make_error(file, "baseColorFactor values must be in [0, 1]", 0, 0, where + ".pbrMetallicRoughness.baseColorFactor");
            m.base_colour[c] = static_cast<float>(f[static_cast<size_t>(c)]);
        }
        if (src.alphaMode == "MASK") {
            if (!std::isfinite(src.alphaCutoff) || src.alphaCutoff < 0.0)
                return make_error(file, "alphaCutoff must be a number of at least 0", 0, 0, where + ".alphaCutoff");
            m.alpha_cutoff = static_cast<float>(std::min(src.alphaCutoff, 1.0));
            if (src.alphaCutoff > 1.0) out->notes.push_back(where + ": alphaCutoff above 1: no fragment of the material is drawn");
        } else if (src.alphaMode == "BLEND") {
            m.alpha_cutoff = 0.5f;
            out->notes.push_back(where + ": alphaMode BLEND is drawn alpha-tested at 0.5 (a crowd is not sorted back to front)");
        } else if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty()) {
            return make_error(file, "alphaMode '" + src.alphaMode + "' is none of OPAQUE, MASK, BLEND", 0, 0, where + ".alphaMode");
        }
        const tinygltf::TextureInfo& info = src.pbrMetallicRoughness.baseColorTexture;
        if (info.index >= 0) {
            const std::string tw = where + ".pbrMetallicRoughness.baseColorTexture";
            if (static_cast<size_t>(info.index) >= model.textures.size())
                return make_error(file, "texture " + std::to_string(info.index) + " is out of range (the file has " + std::to_string(model.textures.size()) + " textures)", 0, 0, tw);
            if (info.texCoord < 0) return make_error(file, "texCoord " + std::to_string(info.texCoord) + " is negative", 0, 0, tw);
            int texcoord = info.texCoord;
            glm::mat3 transform(1.0f);
            if (const auto ext = info.extensions.find("KHR_texture_transform"); ext != info.extensions.end()) {
                Result<glm::mat3> m3 = texture_transform(ext->second, file, tw + ".extensions.KHR_texture_transform", &texcoord);
                if (!m3.ok()) return m3.error();
                transform = m3.value();
                ++transformed;
            }
            const tinygltf::Texture& tex = model.textures[static_cast<size_t>(info.index)];
            const std::string xw = "textures[" + std::to_string(info.index) + "]";
            bool from_webp = false;
            Result<int> source = texture_image(tex, file, xw, &from_webp);
            if (!source.ok()) return source.error();
            if (source.value() < 0 || static_cast<size_t>(source.value()) >= model.images.size()) {
                out->notes.push_back(xw + ": no usable image source (" + std::to_string(source.value()) + "); " + m.name + " drawn untextured");
            } else if (tex.sampler >= static_cast<int>(model.samplers.size())) {
                return make_error(file, "sampler " + std::to_string(tex.sampler) + " is out of range", 0, 0, xw);
            } else {
                // The image as a texture of the type (decoded once per image), or -2 when it cannot be used.
                auto texture_of = [&](size_t img) {
                    const tinygltf::Image& image = model.images[img];
                    if (texture_of_image[img] != -1) return texture_of_image[img];
                    if (image.image.empty() || image.width <= 0 || image.height <= 0 || image.component != 4 || image.bits != 8)
                        return texture_of_image[img] = -2;
                    TextureImage t;
                    const std::string iw = "images[" + std::to_string(img) + "]";
                    t.name = iw + (image.name.empty() ? image.uri.empty() ? "" : " '" + image.uri + "'" : " '" + image.name + "'");
                    t.width = static_cast<uint32_t>(image.width);
                    t.height = static_cast<uint32_t>(image.height);
                    t.rgba = image.image;
                    if (tex.sampler >= 0) {
                        const tinygltf::Sampler& sm = model.samplers[static_cast<size_t>(tex.sampler)];
                        t.wrap_u = wrap_of(sm.wrapS);
                        t.wrap_v = wrap_of(sm.wrapT);
                        t.nearest = sm.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
                    }
                    texture_of_image[img] = static_cast<int>(out->textures.size());
                    out->textures.push_back(std::move(t));
                    return texture_of_image[img];
                };
                const auto img = static_cast<size_t>(source.value());
                int texture = texture_of(img);
                webp += texture >= 0 && from_webp ? 1 : 0;
                // An unusable WebP source with a usable fallback `source`: the fallback is drawn.
                if (texture < 0 && from_webp && source.value() != tex.source && tex.source >= 0 && static_cast<size_t>(tex.source) < model.images.size()) {
                    texture = texture_of(static_cast<size_t>(tex.source));
                    if (texture >= 0)
                        out->notes.push_back(xw + ": its WebP images[" + std::to_string(img) + "] could not be used; the fallback images[" +
                                             std::to_string(tex.source) + "] is drawn");
                }
                if (texture >= 0) {
                    m.texture = texture;
                    (*uv)[i] = MaterialUv{texcoord, transform};
                } else {
                    out->notes.push_back("images[" + std::to_string(img) + "]: image could not be used; " + m.name + " drawn with its base colour only");
                }
            }
        }
        out->materials.push_back(std::move(m));
    }
    if (unlit > 0)
        out->notes.push_back("KHR_materials_unlit: " + std::to_string(unlit) + " material" + (unlit == 1 ? "" : "s") +
                             " drawn without lighting (their impostors, relit from baked normals, are lit)");
    if (webp > 0)
        out->notes.push_back(std::string(kWebpExtension) + ": " + std::to_string(webp) + " material texture" + (webp == 1 ? "" : "s") +
                             " drawn from WebP images (libwebp)");
    if (transformed > 0)
        out->notes.push_back("KHR_texture_transform applied to the texture coordinates of " + std::to_string(transformed) + " material" +
                             (transformed == 1 ? "" : "s"));
    return {};
}

}  // namespace aloha::gltf_detail
