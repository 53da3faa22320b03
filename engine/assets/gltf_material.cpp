// glTF materials for the character loader: base colour factor, alpha mode, KHR_materials_unlit, metallic and
// roughness factors, and the five textures the crowd renderer draws: base colour, normal (with its scale),
// occlusion (with its strength), emissive (emissiveFactor, KHR_materials_emissive_strength) and
// metallic-roughness. Each texture has its texCoord set, KHR_texture_transform, sampler wrap and filter modes and
// EXT_texture_webp's source. A factor that scales a texture is baked into a copy of its image
// (gltf_texture_bake.cpp), so the renderer reads every input as it is. A primitive has one UV set: a texture on
// another set than its material's first one is left out with a note.
#include "engine/assets/gltf_detail.hpp"
#include "engine/assets/gltf_texture_bake.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace aloha::gltf_detail {

namespace {

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

// A material's texture reference (glTF textureInfo, normalTextureInfo, occlusionTextureInfo).
struct TextureRef {
    int index = -1;
    int texcoord = 0;
    const tinygltf::ExtensionMap* extensions = nullptr;
};

// A texture reference resolved: the decoded image it draws, its sampler and its UV set.
struct ResolvedTexture {
    size_t image = 0;
    int sampler = -1;
    MaterialUv uv;
    bool transformed = false;  // KHR_texture_transform given
    bool from_webp = false;    // `image` is the texture's EXT_texture_webp source
};

// Reads the materials of one file into a GltfCharacter, decoding (baking) each texture once.
class MaterialReader {
public:
    MaterialReader(const tinygltf::Model& model, const std::string& file, GltfCharacter* out) : model_(model), file_(file), out_(out) {}

    // Reads every material; `uv` gets each one's UV set (see read_materials).
    Status read(std::vector<MaterialUv>* uv) {
        uv->assign(model_.materials.size(), MaterialUv{});
        for (size_t i = 0; i < model_.materials.size(); ++i) {
            Result<SurfaceMaterial> m = material(i, &(*uv)[i]);
            if (!m.ok()) return m.error();
            out_->materials.push_back(std::move(m).value());
        }
        add_notes();
        return {};
    }

private:
    // Material `i`; its UV set (that of its first drawn texture) goes to `uv`.
    Result<SurfaceMaterial> material(size_t i, MaterialUv* uv) {
        const tinygltf::Material& src = model_.materials[i];
        const std::string where = "materials[" + std::to_string(i) + "]";
        SurfaceMaterial m;
        m.name = src.name.empty() ? "material" + std::to_string(i) : src.name;
        m.double_sided = src.doubleSided;
        m.unlit = src.extensions.count("KHR_materials_unlit") > 0;
        unlit_ += m.unlit ? 1 : 0;
        Result<glm::vec4> base = factors<4>(src.pbrMetallicRoughness.baseColorFactor, where + ".pbrMetallicRoughness.baseColorFactor");
        if (!base.ok()) return base.error();
        m.base_colour = base.value();
        if (Status s = alpha(src, where, &m); !s.ok()) return s.error();
        const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
        Result<TextureBake> bake = bake_of(src, where);
        if (!bake.ok()) return bake.error();
        m.metallic_roughness = !m.unlit;  // glTF's model; an unlit material shows its base colour only
        m.metallic = bake.value().metallic;
        m.roughness = bake.value().roughness;
        metallic_ += m.metallic_roughness && m.metallic > 0.0f ? 1 : 0;  // metalness factor above 0
        const struct {
            TextureRole role;
            TextureRef ref;
            std::string at;
            int* slot;
        } slots[] = {
            {TextureRole::BaseColour, {pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, &pbr.baseColorTexture.extensions},
             where + ".pbrMetallicRoughness.baseColorTexture", &m.texture},
            {TextureRole::Normal, {src.normalTexture.index, src.normalTexture.texCoord, &src.normalTexture.extensions}, where + ".normalTexture", &m.normal_texture},
            {TextureRole::Occlusion, {src.occlusionTexture.index, src.occlusionTexture.texCoord, &src.occlusionTexture.extensions},
             where + ".occlusionTexture", &m.occlusion_texture},
            {TextureRole::Emissive, {src.emissiveTexture.index, src.emissiveTexture.texCoord, &src.emissiveTexture.extensions},
             where + ".emissiveTexture", &m.emissive_texture},
            {TextureRole::MetallicRoughness,
             {pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, &pbr.metallicRoughnessTexture.extensions},
             where + ".pbrMetallicRoughness.metallicRoughnessTexture", &m.metallic_roughness_texture},
        };
        for (const auto& s : slots) {
            if (s.ref.index < 0 || (m.unlit && s.role == TextureRole::MetallicRoughness)) continue;
            Result<std::optional<ResolvedTexture>> r = resolve(s.ref, s.at, m.name);
            if (!r.ok()) return r.error();
            if (!r.value()) continue;
            const ResolvedTexture& t = *r.value();
            if (uv->texcoord < 0) {
                *uv = t.uv;
            } else if (uv->texcoord != t.uv.texcoord || uv->transform != t.uv.transform) {
                out_->notes.push_back(s.at + ": on TEXCOORD_" + std::to_string(t.uv.texcoord) + " where the material's first texture is on TEXCOORD_" +
                                      std::to_string(uv->texcoord) + (uv->transform != t.uv.transform ? " (or another KHR_texture_transform)" : "") +
                                      "; a primitive carries one UV set, so " + m.name + " is drawn without it");
                continue;
            }
            *s.slot = texture(t, s.role, bake.value());
            drawn_[static_cast<size_t>(s.role)] += 1;
            transformed_ += t.transformed ? 1 : 0;
            webp_ += t.from_webp ? 1 : 0;
        }
        // An emissive factor without a texture: a one-texel emissive texture of that colour.
        if (m.emissive_texture < 0 && bake.value().emissive != glm::vec3(0.0f)) {
            m.emissive_texture = static_cast<int>(out_->textures.size());
            out_->textures.push_back(constant_emissive(bake.value().emissive, where + ".emissiveFactor"));
            drawn_[static_cast<size_t>(TextureRole::Emissive)] += 1;
        }
        return m;
    }

    // `n` factors from `v` (glTF's baseColorFactor, emissiveFactor), each in [0, 1].
    template <int n>
    Result<glm::vec<n, float>> factors(const std::vector<double>& v, const std::string& where) const {
        if (v.size() != n) return make_error(file_, "has " + std::to_string(v.size()) + " values, expected " + std::to_string(n), 0, 0, where);
        glm::vec<n, float> out(0.0f);
        for (size_t c = 0; c < v.size(); ++c) {
            if (!std::isfinite(v[c]) || v[c] < 0.0 || v[c] > 1.0) return make_error(file_, "values must be in [0, 1]", 0, 0, where);
            out[static_cast<int>(c)] = static_cast<float>(v[c]);
        }
        return out;
    }

    // The alpha mode: MASK at its cutoff, BLEND alpha-tested at 0.5, OPAQUE (or none) drawn opaque.
    Status alpha(const tinygltf::Material& src, const std::string& where, SurfaceMaterial* m) {
        if (src.alphaMode == "MASK") {
            if (!std::isfinite(src.alphaCutoff) || src.alphaCutoff < 0.0) return make_error(file_, "alphaCutoff must be a number of at least 0", 0, 0, where + ".alphaCutoff");
            m->alpha_cutoff = static_cast<float>(std::min(src.alphaCutoff, 1.0));
            if (src.alphaCutoff > 1.0) out_->notes.push_back(where + ": alphaCutoff above 1: no fragment of the material is drawn");
        } else if (src.alphaMode == "BLEND") {
            m->alpha_cutoff = 0.5f;
            out_->notes.push_back(where + ": alphaMode BLEND is drawn alpha-tested at 0.5 (a crowd is not sorted back to front)");
        } else if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty()) {
            return make_error(file_, "alphaMode '" + src.alphaMode + "' is none of OPAQUE, MASK, BLEND", 0, 0, where + ".alphaMode");
        }
        return {};
    }

    // The factors baked into the material's normal, occlusion, emissive and metallic-roughness textures, checked.
    Result<TextureBake> bake_of(const tinygltf::Material& src, const std::string& where) const {
        TextureBake b;
        b.normal_scale = static_cast<float>(src.normalTexture.scale);
        if (!std::isfinite(src.normalTexture.scale) || !std::isfinite(b.normal_scale))
            return make_error(file_, "scale is NaN, infinite or out of float range", 0, 0, where + ".normalTexture.scale");
        if (!std::isfinite(src.occlusionTexture.strength) || src.occlusionTexture.strength < 0.0 || src.occlusionTexture.strength > 1.0)
            return make_error(file_, "strength must be in [0, 1]", 0, 0, where + ".occlusionTexture.strength");
        b.occlusion_strength = static_cast<float>(src.occlusionTexture.strength);
        Result<glm::vec3> emissive = factors<3>(src.emissiveFactor, where + ".emissiveFactor");
        if (!emissive.ok()) return emissive.error();
        b.emissive = emissive.value();
        if (const auto ext = src.extensions.find("KHR_materials_emissive_strength"); ext != src.extensions.end()) {
            const std::string at = where + ".extensions.KHR_materials_emissive_strength.emissiveStrength";
            if (!ext->second.IsObject()) return make_error(file_, "is not an object", 0, 0, where + ".extensions.KHR_materials_emissive_strength");
            if (ext->second.Has("emissiveStrength")) {
                const tinygltf::Value& v = ext->second.Get("emissiveStrength");
                const double s = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
                if (!std::isfinite(s) || s < 0.0 || s > 1e6) return make_error(file_, "must be a number in [0, 1e6]", 0, 0, at);
                b.emissive *= static_cast<float>(s);
                if (std::max({b.emissive.r, b.emissive.g, b.emissive.b}) > 1.0f) clipped_emissive_ += 1;
            }
        }
        for (const auto& [value, key, field] : {std::tuple{src.pbrMetallicRoughness.metallicFactor, "metallicFactor", &b.metallic},
                                                std::tuple{src.pbrMetallicRoughness.roughnessFactor, "roughnessFactor", &b.roughness}}) {
            if (!std::isfinite(value) || value < 0.0 || value > 1.0)
                return make_error(file_, "must be in [0, 1]", 0, 0, where + ".pbrMetallicRoughness." + key);
            *field = static_cast<float>(value);
        }
        return b;
    }

    // Whether image `img` was decoded into RGBA8 (decode_image).
    bool usable(int img) const {
        if (img < 0 || static_cast<size_t>(img) >= model_.images.size()) return false;
        const tinygltf::Image& image = model_.images[static_cast<size_t>(img)];
        return !image.image.empty() && image.width > 0 && image.height > 0 && image.component == 4 && image.bits == 8;
    }

    // Resolves a material's texture reference at `where`: errors for malformed references, nullopt with a note
    // when its image cannot be drawn (the material is then drawn without it).
    Result<std::optional<ResolvedTexture>> resolve(const TextureRef& ref, const std::string& where, const std::string& material) {
        if (static_cast<size_t>(ref.index) >= model_.textures.size())
            return make_error(file_, "texture " + std::to_string(ref.index) + " is out of range (the file has " + std::to_string(model_.textures.size()) + " textures)",
                              0, 0, where);
        if (ref.texcoord < 0) return make_error(file_, "texCoord " + std::to_string(ref.texcoord) + " is negative", 0, 0, where);
        ResolvedTexture out;
        out.uv.texcoord = ref.texcoord;
        if (const auto ext = ref.extensions->find("KHR_texture_transform"); ext != ref.extensions->end()) {
            Result<glm::mat3> m3 = texture_transform(ext->second, file_, where + ".extensions.KHR_texture_transform", &out.uv.texcoord);
            if (!m3.ok()) return m3.error();
            out.uv.transform = m3.value();
            out.transformed = true;
        }
        const tinygltf::Texture& tex = model_.textures[static_cast<size_t>(ref.index)];
        const std::string xw = "textures[" + std::to_string(ref.index) + "]";
        bool from_webp = false;
        Result<int> source = texture_image(tex, file_, xw, &from_webp);
        if (!source.ok()) return source.error();
        if (source.value() < 0 || static_cast<size_t>(source.value()) >= model_.images.size()) {
            out_->notes.push_back(xw + ": no usable image source (" + std::to_string(source.value()) + "); " + material + " drawn without it");
            return std::optional<ResolvedTexture>();
        }
        if (tex.sampler >= static_cast<int>(model_.samplers.size())) return make_error(file_, "sampler " + std::to_string(tex.sampler) + " is out of range", 0, 0, xw);
        out.sampler = tex.sampler;
        int img = source.value();
        if (!usable(img) && from_webp && img != tex.source && usable(tex.source)) {
            // An unusable WebP source with a usable fallback `source`: the fallback is drawn.
            if (fallback_noted_.insert(ref.index).second)
                out_->notes.push_back(xw + ": its WebP images[" + std::to_string(img) + "] could not be used; the fallback images[" + std::to_string(tex.source) +
                                      "] is drawn");
            img = tex.source;
        } else if (!usable(img)) {
            out_->notes.push_back("images[" + std::to_string(img) + "]: image could not be used; " + material + " drawn without it (" + where + ")");
            return std::optional<ResolvedTexture>();
        } else {
            out.from_webp = from_webp;
        }
        out.image = static_cast<size_t>(img);
        return std::optional<ResolvedTexture>(out);
    }

    // The texture drawing `t` in role `role` with `bake`'s factor for that role baked in: made once per image,
    // sampler, role and factor; its index in out_->textures.
    int texture(const ResolvedTexture& t, TextureRole role, const TextureBake& bake) {
        const glm::vec3 f = role == TextureRole::Normal ? glm::vec3(bake.normal_scale) : role == TextureRole::Occlusion ? glm::vec3(bake.occlusion_strength)
                            : role == TextureRole::Emissive ? bake.emissive
                            : role == TextureRole::MetallicRoughness ? glm::vec3(bake.metallic, bake.roughness, 0.0f) : glm::vec3(1.0f);
        const auto key = std::make_tuple(t.image, t.sampler, static_cast<int>(role), f.x, f.y, f.z);
        if (const auto it = made_.find(key); it != made_.end()) return it->second;
        const tinygltf::Image& image = model_.images[t.image];
        TextureImage out;
        const std::string iw = "images[" + std::to_string(t.image) + "]";
        out.name = iw + (image.name.empty() ? image.uri.empty() ? "" : " '" + image.uri + "'" : " '" + image.name + "'");
        out.width = static_cast<uint32_t>(image.width);
        out.height = static_cast<uint32_t>(image.height);
        out.rgba = image.image;
        if (t.sampler >= 0) {
            const tinygltf::Sampler& sm = model_.samplers[static_cast<size_t>(t.sampler)];
            out.wrap_u = wrap_of(sm.wrapS);
            out.wrap_v = wrap_of(sm.wrapT);
            out.nearest = sm.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        }
        bake_texture(role, bake, &out);
        const int id = static_cast<int>(out_->textures.size());
        out_->textures.push_back(std::move(out));
        made_.emplace(key, id);
        return id;
    }

    // The file's notes on materials, one per kind.
    void add_notes() {
        auto plural = [](size_t n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); };
        if (unlit_ > 0)
            out_->notes.push_back("KHR_materials_unlit: " + plural(unlit_, "material") + " drawn without lighting (their impostors too)");
        if (webp_ > 0) out_->notes.push_back(std::string(kWebpExtension) + ": " + plural(webp_, "material texture") + " drawn from WebP images (libwebp)");
        if (transformed_ > 0) out_->notes.push_back("KHR_texture_transform applied to the texture coordinates of " + plural(transformed_, "material texture"));
        const size_t normal = drawn_[static_cast<size_t>(TextureRole::Normal)], occlusion = drawn_[static_cast<size_t>(TextureRole::Occlusion)],
                     emissive = drawn_[static_cast<size_t>(TextureRole::Emissive)],
                     metallic_roughness = drawn_[static_cast<size_t>(TextureRole::MetallicRoughness)];
        std::string maps;
        for (const auto& [n, what] : {std::pair{normal, "normal map"}, std::pair{occlusion, "occlusion map"}, std::pair{emissive, "emissive input"},
                                      std::pair{metallic_roughness, "metallic-roughness map"}})
            if (n > 0) maps += (maps.empty() ? "" : ", ") + plural(n, what);
        if (!maps.empty())
            out_->notes.push_back("material inputs drawn besides base colour: " + maps +
                                  (normal + occlusion > 0 ? " (normal and occlusion maps by the levels lit per pixel; impostors bake them in)" : ""));
        if (metallic_ > 0)
            out_->notes.push_back(plural(metallic_, "material") + " with a metalness factor above 0: impostors show metals under an even white sky, without the "
                                  "key light's highlight");
        if (clipped_emissive_ > 0)
            out_->notes.push_back("KHR_materials_emissive_strength: " + plural(clipped_emissive_, "material") +
                                  " brighter than 1 drawn clipped to the display's white (no HDR target)");
    }

    const tinygltf::Model& model_;
    const std::string& file_;
    GltfCharacter* out_;
    std::map<std::tuple<size_t, int, int, float, float, float>, int> made_;  // (image, sampler, role, factor) -> texture
    std::set<int> fallback_noted_;
    size_t drawn_[5] = {0, 0, 0, 0, 0};
    size_t unlit_ = 0, webp_ = 0, transformed_ = 0, metallic_ = 0;
    mutable size_t clipped_emissive_ = 0;
};

}  // namespace

Status read_materials(const tinygltf::Model& model, const std::string& file, GltfCharacter* out, std::vector<MaterialUv>* uv) {
    return MaterialReader(model, file, out).read(uv);
}

}  // namespace aloha::gltf_detail
