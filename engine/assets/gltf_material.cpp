// glTF materials for the character loader: base colour factor, base colour texture (its texCoord
// set, sampler wrap and filter modes) and the decoding of the images they use (stb_image, RGBA8).
#include "engine/assets/gltf_detail.hpp"

#include <stb_image.h>

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

}  // namespace

bool decode_image(tinygltf::Image* image, int index, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void* user) {
    auto* log = static_cast<ImageDecodeLog*>(user);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) {
        log->failures.emplace_back(index, std::string("not a PNG or JPEG image stb_image can read (") + stbi_failure_reason() + ")");
        return true;
    }
    if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide) {
        log->failures.emplace_back(index, std::to_string(w) + " x " + std::to_string(h) + " pixels exceeds the limit of " + std::to_string(kMaxImageSide) +
                                              " x " + std::to_string(kMaxImageSide));
        return true;
    }
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

Status read_materials(const tinygltf::Model& model, const std::string& file, GltfCharacter* out, std::vector<int>* texcoord) {
    std::vector<int> texture_of_image(model.images.size(), -1);  // index into out->textures, -2 = unusable
    texcoord->assign(model.materials.size(), -1);
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& src = model.materials[i];
        const std::string where = "materials[" + std::to_string(i) + "]";
        SurfaceMaterial m;
        m.name = src.name.empty() ? "material" + std::to_string(i) : src.name;
        m.double_sided = src.doubleSided;
        const std::vector<double>& f = src.pbrMetallicRoughness.baseColorFactor;
        if (f.size() != 4) return make_error(file, "baseColorFactor has " + std::to_string(f.size()) + " values, expected 4", 0, 0, where + ".pbrMetallicRoughness");
        for (int c = 0; c < 4; ++c) {
            if (!std::isfinite(f[static_cast<size_t>(c)]) || f[static_cast<size_t>(c)] < 0.0 || f[static_cast<size_t>(c)] > 1.0)
                return make_error(file, "baseColorFactor values must be in [0, 1]", 0, 0, where + ".pbrMetallicRoughness.baseColorFactor");
            m.base_colour[c] = static_cast<float>(f[static_cast<size_t>(c)]);
        }
        if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty())
            out->notes.push_back(where + ": alphaMode " + src.alphaMode + " is drawn opaque");
        const tinygltf::TextureInfo& info = src.pbrMetallicRoughness.baseColorTexture;
        if (info.index >= 0) {
            const std::string tw = where + ".pbrMetallicRoughness.baseColorTexture";
            if (static_cast<size_t>(info.index) >= model.textures.size())
                return make_error(file, "texture " + std::to_string(info.index) + " is out of range (the file has " + std::to_string(model.textures.size()) + " textures)", 0, 0, tw);
            if (info.texCoord < 0) return make_error(file, "texCoord " + std::to_string(info.texCoord) + " is negative", 0, 0, tw);
            if (info.extensions.count("KHR_texture_transform")) out->notes.push_back(tw + ": KHR_texture_transform is not applied");
            const tinygltf::Texture& tex = model.textures[static_cast<size_t>(info.index)];
            const std::string xw = "textures[" + std::to_string(info.index) + "]";
            if (tex.source < 0 || static_cast<size_t>(tex.source) >= model.images.size()) {
                out->notes.push_back(xw + ": no usable image source (" + std::to_string(tex.source) + "); " + m.name + " drawn untextured");
            } else if (tex.sampler >= static_cast<int>(model.samplers.size())) {
                return make_error(file, "sampler " + std::to_string(tex.sampler) + " is out of range", 0, 0, xw);
            } else {
                const auto img = static_cast<size_t>(tex.source);
                const tinygltf::Image& image = model.images[img];
                const std::string iw = "images[" + std::to_string(img) + "]";
                if (texture_of_image[img] == -1) {
                    if (image.image.empty() || image.width <= 0 || image.height <= 0 || image.component != 4 || image.bits != 8) {
                        texture_of_image[img] = -2;
                    } else {
                        TextureImage t;
                        t.name = iw + (image.name.empty() ? image.uri.empty() ? "" : " '" + image.uri + "'" : " '" + image.name + "'");
                        t.width = static_cast<uint32_t>(image.width);
                        t.height = static_cast<uint32_t>(image.height);
                        t.rgba = image.image;
                        if (tex.sampler >= 0) {
                            const tinygltf::Sampler& s = model.samplers[static_cast<size_t>(tex.sampler)];
                            t.wrap_u = wrap_of(s.wrapS);
                            t.wrap_v = wrap_of(s.wrapT);
                            t.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
                        }
                        texture_of_image[img] = static_cast<int>(out->textures.size());
                        out->textures.push_back(std::move(t));
                    }
                }
                if (texture_of_image[img] >= 0) {
                    m.texture = texture_of_image[img];
                    (*texcoord)[i] = info.texCoord;
                } else {
                    out->notes.push_back(iw + ": image could not be used; " + m.name + " drawn with its base colour only");
                }
            }
        }
        out->materials.push_back(std::move(m));
    }
    return {};
}

}  // namespace aloha::gltf_detail
