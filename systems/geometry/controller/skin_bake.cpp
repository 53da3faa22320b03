// Keys, code version and payloads of the generated body's cached bakes.
#include "systems/geometry/controller/skin_bake.hpp"

#include "engine/core/build_id.hpp"
#include "systems/geometry/controller/bake_code_digest.hpp"

#include <meshoptimizer.h>

#include <cmath>
#include <mutex>

namespace aloha {
namespace {

// The layouts written as raw bytes have no padding (their bytes are all value bytes).
static_assert(sizeof(BlendBinding) == kBlendInfluences * (4 + sizeof(GridParam) + sizeof(GridCell) + 12 + 4));
static_assert(sizeof(GridParam) == 8 && sizeof(GridCell) == 24);
static_assert(sizeof(glm::u16vec4) == 8 && sizeof(glm::uvec3) == 12 && sizeof(glm::vec3) == 12 && sizeof(glm::mat4) == 64);

// Kinds of entry (the first bytes of a key); a new layout of a payload gets a new number.
constexpr uint32_t kSkinLayerKind = 0x534b4c02;  // "SKL" v2: keyed by a digest
constexpr uint32_t kSurfaceMapKind = 0x534d5002; // "SMP" v2: keyed by content
constexpr uint32_t kSimplifiedKind = 0x53494d01; // "SIM" v1: simplified triangle lists, keyed by content

// A skin layer's fields in payload order, handed to `io` one by one (writing and reading alike).
template <class Layer, class Io>
void skin_layer_fields(Layer& l, Io&& io) {
    io(l.theta_steps);
    io(l.phi_steps);
    io(l.rest_positions);
    io(l.rest_normals);
    io(l.indices);
    io(l.bindings);
    io(l.dominant_muscle);
    io(l.joints);
    io(l.weights);
}

template <class T>
void write_field(ByteWriter& w, const T& v) { w.put(v); }
template <class T>
void write_field(ByteWriter& w, const std::vector<T>& v) { w.put_vector(v); }
template <class T>
void read_field(ByteReader& r, T& v) { r.get(v); }
template <class T>
void read_field(ByteReader& r, std::vector<T>& v) { r.get_vector(v); }

}  // namespace

Result<std::vector<uint8_t>> skin_bake_code_version() {
    static std::once_flag once;
    static std::optional<Result<std::vector<uint8_t>>> version;
    std::call_once(once, [] {
        // The shared libraries' build-ids: their code is not in the digest (a static meshoptimizer gives the
        // program's own id, which only makes the version stricter).
        float (*expf_fn)(float) = &::expf;
        void (*meshopt_fn)(unsigned int*, const unsigned int*, size_t, size_t) = &meshopt_optimizeVertexCache;
        const uintptr_t code[] = {reinterpret_cast<uintptr_t>(meshopt_fn), reinterpret_cast<uintptr_t>(expf_fn)};
        Result<std::vector<uint8_t>> ids = build_ids_of(code);
        if (!ids.ok()) {
            version.emplace(ids.error());
            return;
        }
        ByteWriter w;
        w.put_string(kBakeCodeDigest);
        w.put_vector(ids.value());
        version.emplace(w.take());
    });
    return *version;
}

std::vector<uint8_t> skin_bake_inputs(const MuscleSet& muscles, std::span<const int16_t> parents,
                                      std::span<const glm::mat4> rest_model, std::span<const float> proxy_radii,
                                      float length_scale) {
    ByteWriter w;
    w.put<int32_t>(muscles.joint_count);
    w.put<uint64_t>(muscles.names.size());
    for (const std::string& n : muscles.names) w.put_string(n);
    const auto put_vectors = [&w](const auto&... v) { (w.put_vector(v), ...); };
    put_vectors(muscles.origin_joint, muscles.insertion_joint, muscles.origin_offset, muscles.insertion_offset,
                muscles.depth_hint, muscles.volume, muscles.ratio, muscles.exponents, muscles.volume_factor,
                muscles.fat_thickness, muscles.rest_length, muscles.fat_region);
    w.put<uint64_t>(muscles.fat_regions.size());
    for (const FatRegion& r : muscles.fat_regions) {  // field by field: std::optional has padding bytes
        w.put_string(r.name);
        for (const std::optional<float>& v : {r.normal_hz, r.normal_damping, r.lateral_hz, r.max_strain}) {
            w.put<uint8_t>(v ? 1 : 0);
            w.put<float>(v ? *v : 0.0f);
        }
    }
    w.put_vector(parents);
    w.put_vector(rest_model);
    w.put_vector(proxy_radii);
    w.put<float>(length_scale);
    return w.take();
}

std::vector<uint8_t> skin_layer_key(std::span<const uint8_t> inputs, uint32_t theta_steps, uint32_t phi_steps) {
    ByteWriter w;
    w.put(theta_steps);
    w.put(phi_steps);
    w.put_vector(inputs);
    return digest_key(kSkinLayerKind, w.bytes());
}

std::vector<uint8_t> surface_map_key(std::span<const glm::vec3> source, std::span<const uint32_t> source_indices,
                                     std::span<const glm::vec3> target) {
    ByteWriter inputs;
    inputs.put_vector(source);
    inputs.put_vector(source_indices);
    inputs.put_vector(target);
    return digest_key(kSurfaceMapKind, inputs.bytes());
}

std::vector<uint8_t> simplified_indices_key(std::span<const glm::vec3> positions, std::span<const uint32_t> indices, float target_error) {
    ByteWriter inputs;
    inputs.put_vector(positions);
    inputs.put_vector(indices);
    inputs.put(target_error);
    return digest_key(kSimplifiedKind, inputs.bytes());
}

std::vector<uint8_t> write_skin_layer(const SkinLayer& layer) {
    ByteWriter w;
    skin_layer_fields(layer, [&w](const auto& field) { write_field(w, field); });
    return w.take();
}

std::optional<SkinLayer> read_skin_layer(std::span<const uint8_t> bytes, uint32_t muscle_count) {
    ByteReader r(bytes);
    SkinLayer l;
    skin_layer_fields(l, [&r](auto& field) { read_field(r, field); });
    const size_t n = l.rest_positions.size();
    if (!r.done() || n == 0 || l.rest_normals.size() != n || l.bindings.size() != n || l.dominant_muscle.size() != n ||
        l.joints.size() != l.weights.size() || (!l.joints.empty() && l.joints.size() != n) || l.indices.empty() ||
        l.indices.size() % 3 != 0)
        return std::nullopt;
    for (const uint32_t i : l.indices)
        if (i >= n) return std::nullopt;
    for (size_t v = 0; v < n; ++v) {
        if (l.dominant_muscle[v] >= muscle_count) return std::nullopt;
        for (int k = 0; k < kBlendInfluences; ++k)
            if (l.bindings[v].muscle[k] >= muscle_count) return std::nullopt;
    }
    return l;
}

std::vector<uint8_t> write_surface_map(const SurfaceMap& map) {
    ByteWriter w;
    w.put_vector(map.corners);
    w.put_vector(map.bary);
    return w.take();
}

std::optional<SurfaceMap> read_surface_map(std::span<const uint8_t> bytes, size_t source_vertices, size_t target_vertices) {
    ByteReader r(bytes);
    SurfaceMap m;
    r.get_vector(m.corners);
    r.get_vector(m.bary);
    if (!r.done() || m.corners.size() != target_vertices || m.bary.size() != target_vertices) return std::nullopt;
    for (const glm::uvec3& c : m.corners)
        if (c.x >= source_vertices || c.y >= source_vertices || c.z >= source_vertices) return std::nullopt;
    return m;
}

std::vector<uint8_t> write_triangle_list(std::span<const uint32_t> indices) {
    ByteWriter w;
    w.put_vector(indices);
    return w.take();
}

std::optional<std::vector<uint32_t>> read_triangle_list(std::span<const uint8_t> bytes, size_t vertices) {
    ByteReader r(bytes);
    std::vector<uint32_t> indices;
    r.get_vector(indices);
    if (!r.done() || indices.size() % 3 != 0) return std::nullopt;
    for (const uint32_t v : indices)
        if (v >= vertices) return std::nullopt;
    return indices;
}

}  // namespace aloha
