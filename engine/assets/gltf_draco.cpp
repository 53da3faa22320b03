// KHR_draco_mesh_compression for the glTF loader, run by prepare_buffers() before any accessor is read:
// each primitive's compressed bytes are decoded with Draco, and every attribute the extension names and the
// triangle indices are written, converted to what the primitive's accessors say (component type, type,
// normalized), into buffers of their own that those accessors then point at, so the accessor reader sees
// plain data. Every id, count, mapping and value of the decoded mesh is checked before it is used. Draco
// itself runs behind libaloha_draco.so (draco_mesh.hpp), which this file calls without seeing a Draco type.
#include "engine/assets/draco_mesh.hpp"
#include "engine/assets/gltf_detail.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <utility>

namespace aloha::gltf_detail {

namespace {

const std::string kDraco(kDracoExtension);

template <class T>
void store(unsigned char* out, T v) { std::memcpy(out, &v, sizeof(T)); }

// Writes `v` as one component of type `ct` at `out`: floats as they are, normalized integers as round(v * max)
// of v clamped to [-1, 1] (signed) or [0, 1], other integers rounded. False when v is not finite or does not fit.
bool write_component(double v, int ct, bool normalized, unsigned char* out) {
    if (!std::isfinite(v)) return false;
    if (ct == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        const auto f = static_cast<float>(v);
        store(out, f);
        return std::isfinite(f);
    }
    const bool is_signed = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT;
    const size_t bits = 8 * static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(ct)));
    const double hi = std::ldexp(1.0, static_cast<int>(bits - (is_signed ? 1 : 0))) - 1.0, lo = is_signed ? -hi - 1.0 : 0.0;
    const double r = normalized ? std::round(std::clamp(v, is_signed ? -1.0 : 0.0, 1.0) * hi) : std::round(v);
    if (r < lo || r > hi) return false;
    switch (ct) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: store(out, static_cast<int8_t>(r)); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: store(out, static_cast<uint8_t>(r)); break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: store(out, static_cast<int16_t>(r)); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: store(out, static_cast<uint16_t>(r)); break;
        default: store(out, static_cast<uint32_t>(r)); break;
    }
    return true;
}

// Value of point `p` of `att` as accessor `a`'s `comps` components of `comp_size` bytes at `out`: the stored
// numbers unchanged when the types agree (the integer bits mean the same whatever `normalized` says), else
// Draco's value (normalised integers as [0, 1] / [-1, 1]) converted to the accessor's type.
bool convert_value(const DracoAttribute& att, size_t p, const tinygltf::Accessor& a, int comps, size_t comp_size, unsigned char* out) {
    const double* v = att.values.data() + p * static_cast<size_t>(comps);
    const bool same = att.gltf_component == a.componentType;
    for (int c = 0; c < comps; ++c) {
        double x = v[c];
        if (!same && att.normalized && att.type_max > 0) x = std::max(x / static_cast<double>(att.type_max), -1.0);
        if (!write_component(x, a.componentType, same ? false : a.normalized, out + static_cast<size_t>(c) * comp_size)) return false;
    }
    return true;
}

// Appends a buffer holding `bytes` and a tightly packed view over it; returns the view's index.
int add_view(tinygltf::Model* model, std::vector<unsigned char> bytes, int target, const std::string& name) {
    tinygltf::Buffer buffer;
    buffer.name = name;
    buffer.data = std::move(bytes);
    tinygltf::BufferView view;
    view.buffer = static_cast<int>(model->buffers.size());
    view.byteLength = buffer.data.size();
    view.target = target;
    model->buffers.push_back(std::move(buffer));
    model->bufferViews.push_back(view);
    return static_cast<int>(model->bufferViews.size() - 1);
}

// One primitive: `where` names its extension object, `filled` records which accessor was filled from what
// (compressed view, Draco id; -1 for indices) so that two primitives cannot fill one accessor differently.
class PrimitiveDecoder {
public:
    PrimitiveDecoder(tinygltf::Model* model, const std::string& file, const std::string& where, std::map<int, std::pair<int64_t, int64_t>>* filled)
        : model_(model), file_(file), where_(where), filled_(filled) {}

    Status decode(tinygltf::Primitive* prim, const tinygltf::Value& ext) {
        if (!ext.IsObject()) return fail("is not an object");
        if (prim->mode != -1 && prim->mode != TINYGLTF_MODE_TRIANGLES)
            return fail("the primitive's mode is " + std::to_string(prim->mode) + "; Draco data is read as TRIANGLES (4) only");
        view_ = ext.Has("bufferView") ? non_negative_integer(ext.Get("bufferView")) : -1;
        if (view_ < 0) return fail("'bufferView' is missing or not a non-negative integer");
        if (static_cast<size_t>(view_) >= model_->bufferViews.size())
            return fail("bufferView " + std::to_string(view_) + " is out of range (the file has " + std::to_string(model_->bufferViews.size()) + " bufferViews)");
        const tinygltf::BufferView& bv = model_->bufferViews[static_cast<size_t>(view_)];
        const std::string bv_name = "bufferViews[" + std::to_string(view_) + "]";
        if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model_->buffers.size())
            return fail(bv_name + " refers to buffer " + std::to_string(bv.buffer) + ", out of range (the file has " + std::to_string(model_->buffers.size()) +
                        " buffers)");
        const std::vector<unsigned char>& data = model_->buffers[static_cast<size_t>(bv.buffer)].data;
        if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
            return fail(bv_name + "'s byte range " + std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) + " exceeds buffers[" +
                        std::to_string(bv.buffer) + "] of " + std::to_string(data.size()) + " bytes");
        if (!ext.Has("attributes") || !ext.Get("attributes").IsObject()) return fail("'attributes' is missing or not an object");
        const std::string why = decode_draco_mesh(data.data() + bv.byteOffset, bv.byteLength, kMaxGltfAccessorCount, &mesh_);
        if (!why.empty()) return fail("the compressed data in " + bv_name + " is " + why);
        points_ = mesh_.points;
        const tinygltf::Value& attributes = ext.Get("attributes");
        for (const std::string& name : attributes.Keys()) {
            const int64_t id = non_negative_integer(attributes.Get(name));
            if (id < 0 || id > int64_t{UINT32_MAX}) return fail("attributes." + name + " is not a non-negative integer Draco attribute id");
            const auto it = prim->attributes.find(name);
            if (it == prim->attributes.end()) continue;  // no accessor to fill (the spec forbids it, but Khronos' own Box sample has one)
            const auto att = std::find_if(mesh_.attributes.begin(), mesh_.attributes.end(),
                                          [&](const DracoAttribute& d) { return d.unique_id == static_cast<uint32_t>(id); });
            if (att == mesh_.attributes.end()) {
                std::string ids;
                for (const DracoAttribute& d : mesh_.attributes) ids += (ids.empty() ? "" : ", ") + std::to_string(d.unique_id);
                return fail("attribute " + name + " has Draco id " + std::to_string(id) + ", which the decoded mesh does not have (its ids: " + ids + ")");
            }
            if (Status s = attribute(it->second, name, id, *att); !s.ok()) return s;
        }
        return indices(prim);
    }

private:
    Status fail(const std::string& msg) const { return make_error(file_, msg, 0, 0, where_); }

    // Records that accessor `index` is filled from Draco id `id` (-1: indices) of this primitive's data.
    Status claim(int index, int64_t id, const std::string& what) {
        const auto [it, added] = filled_->try_emplace(index, view_, id);
        if (!added && it->second != std::pair<int64_t, int64_t>(view_, id))
            return fail(what + " uses accessors[" + std::to_string(index) + "], which other Draco data already filled; each needs an accessor of its own");
        return {};
    }

    Status attribute(int index, const std::string& name, int64_t id, const DracoAttribute& att) {
        const std::string what = "attribute " + name;
        if (index < 0 || static_cast<size_t>(index) >= model_->accessors.size())
            return fail(what + " refers to accessor " + std::to_string(index) + ", but the file has " + std::to_string(model_->accessors.size()) + " accessors");
        tinygltf::Accessor& a = model_->accessors[static_cast<size_t>(index)];
        const std::string acc = what + "'s accessors[" + std::to_string(index) + "]";
        if (a.type != TINYGLTF_TYPE_SCALAR && a.type != TINYGLTF_TYPE_VEC2 && a.type != TINYGLTF_TYPE_VEC3 && a.type != TINYGLTF_TYPE_VEC4)
            return fail(acc + " is not SCALAR or VEC2 to VEC4");
        if (a.componentType < TINYGLTF_COMPONENT_TYPE_BYTE || a.componentType > TINYGLTF_COMPONENT_TYPE_FLOAT || a.componentType == TINYGLTF_COMPONENT_TYPE_INT)
            return fail(acc + " has component type " + std::to_string(a.componentType) + ", not one of glTF's");
        const int comps = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
        const auto comp_size = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType)));
        if (a.count != points_)
            return fail(acc + " has count " + std::to_string(a.count) + ", but the decoded mesh has " + std::to_string(points_) + " points");
        if (att.components != comps)
            return fail(what + ": Draco attribute " + std::to_string(id) + " has " + std::to_string(att.components) + " components, but its accessor has " +
                        std::to_string(comps));
        if (Status s = claim(index, id, what); !s.ok()) return s;
        std::vector<unsigned char> out(points_ * static_cast<size_t>(comps) * comp_size);
        for (size_t p = 0; p < points_; ++p) {
            if (!convert_value(att, p, a, comps, comp_size, out.data() + p * static_cast<size_t>(comps) * comp_size))
                return fail(what + ": the value of point " + std::to_string(p) + " is not finite or does not fit " + component_name(a.componentType) +
                            (a.normalized ? " (normalized)" : ""));
        }
        a.bufferView = add_view(model_, std::move(out), TINYGLTF_TARGET_ARRAY_BUFFER, "decoded " + where_ + " " + name);
        a.byteOffset = 0;
        return {};
    }

    // The triangle list (3 point indices per face) into the indices accessor, made when the primitive has none.
    Status indices(tinygltf::Primitive* prim) {
        const size_t count = mesh_.indices.size();
        if (prim->indices < 0) {
            tinygltf::Accessor a;
            a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
            a.type = TINYGLTF_TYPE_SCALAR;
            a.count = count;
            model_->accessors.push_back(a);
            prim->indices = static_cast<int>(model_->accessors.size() - 1);
        }
        const int index = prim->indices;
        if (static_cast<size_t>(index) >= model_->accessors.size())
            return fail("indices refer to accessor " + std::to_string(index) + ", but the file has " + std::to_string(model_->accessors.size()) + " accessors");
        tinygltf::Accessor& a = model_->accessors[static_cast<size_t>(index)];
        const std::string acc = "indices accessors[" + std::to_string(index) + "]";
        const int ct = a.componentType;
        if (a.type != TINYGLTF_TYPE_SCALAR ||
            (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            return fail(acc + " is not SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        if (a.count != count)
            return fail(acc + " has count " + std::to_string(a.count) + ", but the decoded mesh has " + std::to_string(count / 3) + " triangles (" +
                        std::to_string(count) + " indices)");
        if (points_ - 1 > (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? 0xFFu : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 0xFFFFu : 0xFFFFFFFFu))
            return fail("the decoded mesh has " + std::to_string(points_) + " points, too many for the " + component_name(ct) + " " + acc);
        if (Status s = claim(index, -1, "indices"); !s.ok()) return s;
        const auto size = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(ct)));
        std::vector<unsigned char> out(count * size);
        for (size_t i = 0; i < count; ++i) write_component(static_cast<double>(mesh_.indices[i]), ct, false, out.data() + i * size);
        a.bufferView = add_view(model_, std::move(out), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, "decoded " + where_ + " indices");
        a.byteOffset = 0;
        return {};
    }

    tinygltf::Model* model_;
    const std::string& file_;
    std::string where_;
    std::map<int, std::pair<int64_t, int64_t>>* filled_;
    int64_t view_ = -1;
    DracoMesh mesh_;
    size_t points_ = 0;
};

}  // namespace

Status decode_draco_primitives(tinygltf::Model* model, const std::string& file, size_t* decoded) {
    std::map<int, std::pair<int64_t, int64_t>> filled;
    for (size_t m = 0; m < model->meshes.size(); ++m)
        for (size_t p = 0; p < model->meshes[m].primitives.size(); ++p) {
            tinygltf::Primitive& prim = model->meshes[m].primitives[p];
            const auto it = prim.extensions.find(kDraco);
            if (it == prim.extensions.end()) continue;
            const std::string where = "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "].extensions." + kDraco;
            if (Status s = PrimitiveDecoder(model, file, where, &filled).decode(&prim, it->second); !s.ok()) return s;
            prim.extensions.erase(it);
            ++*decoded;
        }
    return {};
}

}  // namespace aloha::gltf_detail
