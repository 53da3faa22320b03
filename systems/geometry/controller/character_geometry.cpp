// CharacterGeometry: validation, rest-pose data, mesh bindings and the lazily built caches.
#include "systems/geometry/controller/character_geometry.hpp"

#include "systems/geometry/body_skin/skin_remesh.hpp"
#include "systems/geometry/controller/simplified_indices.hpp"
#include "systems/geometry/controller/skin_bake.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/muscle/superellipsoid.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"
#include "systems/geometry/surface_grid.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <future>

namespace aloha {
namespace {

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite_matrix(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// Every problem of a real mesh, one message each (first offending element named).
void check_mesh(const CharacterMesh& mesh, uint32_t joints, std::vector<std::string>& problems) {
    const size_t n = mesh.positions.size();
    if (n == 0) problems.push_back("mesh has no vertices");
    if (mesh.normals.size() != n) problems.push_back("mesh normals count differs from positions");
    if (mesh.joints.size() != n) problems.push_back("mesh joints count differs from positions");
    if (mesh.weights.size() != n) problems.push_back("mesh weights count differs from positions");
    if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) problems.push_back("mesh indices are not a non-empty triangle list");
    if (!mesh.uvs.empty() && mesh.uvs.size() != n) problems.push_back("mesh UV count differs from positions");
    if (!mesh.vertex_material.empty() && mesh.vertex_material.size() != n) problems.push_back("mesh vertex material count differs from positions");
    if (!mesh.colours.empty() && mesh.colours.size() != n) problems.push_back("mesh colour count differs from positions");
    if (mesh.inverse_bind.size() != joints)
        problems.push_back("mesh has " + std::to_string(mesh.inverse_bind.size()) + " inverse bind matrices for " +
                           std::to_string(joints) + " joints");
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        if (mesh.indices[i] >= n) {
            problems.push_back("mesh index " + std::to_string(i) + " = " + std::to_string(mesh.indices[i]) + " is out of range");
            break;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        if (!finite3(mesh.positions[i])) {
            problems.push_back("mesh vertex " + std::to_string(i) + " is not finite");
            break;
        }
    }
    if (mesh.joints.size() == n && mesh.weights.size() == n) {
        for (size_t i = 0; i < n; ++i) {
            bool bad = false;
            for (int k = 0; k < 4; ++k) bad |= mesh.weights[i][k] != 0.0f && mesh.joints[i][k] >= joints;
            if (bad) {
                problems.push_back("mesh vertex " + std::to_string(i) + " uses a joint outside the skeleton");
                break;
            }
        }
    }
    for (const glm::mat4& m : mesh.inverse_bind) {
        if (!finite_matrix(m)) {
            problems.push_back("mesh has a non-finite inverse bind matrix");
            break;
        }
    }
}

// Box radius of the proxy of joint j: the thickest rest muscle (plus its fat) anchored on the bone
// the box covers (origin on j's parent, or on j for a root), clamped to [2 cm, 15 cm]; 4 cm without.
// Each joint's proxy radius: the thickest muscle on its bone with its fat, within 2-15 cm (4 cm without a muscle) on
// a person, those bounds times `length_scale` on a body of another size.
std::vector<float> proxy_radii_of(const Skeleton& skeleton, const MuscleSet& set, float length_scale) {
    std::vector<float> radii(static_cast<size_t>(skeleton.joint_count()), 0.0f);
    for (size_t j = 0; j < radii.size(); ++j) {
        const int bone = skeleton.parents()[j] < 0 ? static_cast<int>(j) : skeleton.parents()[j];
        float r = 0.0f;
        for (size_t m = 0; m < static_cast<size_t>(set.size()); ++m) {
            if (set.origin_joint[m] != bone) continue;
            const glm::vec3 rr = volume_preserving_radii(set.rest_length[m], set.volume[m], set.ratio[m], set.volume_factor[m]);
            r = std::max(r, std::max(rr.y, rr.z) + set.fat_thickness[m]);
        }
        radii[j] = r > 0.0f ? std::clamp(r, 0.02f * length_scale, 0.15f * length_scale) : 0.04f * length_scale;
    }
    return radii;
}

}  // namespace

std::vector<glm::vec3> skin_mesh_positions(const CharacterMesh& mesh, std::span<const glm::mat4> model) {
    std::vector<glm::vec3> out(mesh.positions.size());
    for (size_t i = 0; i < out.size(); ++i) {
        glm::vec4 p(0.0f);
        for (int k = 0; k < 4; ++k) {
            const float w = mesh.weights[i][k];
            if (w == 0.0f) continue;
            const size_t j = mesh.joints[i][k];
            p += w * (model[j] * (mesh.inverse_bind[j] * glm::vec4(mesh.positions[i], 1.0f)));
        }
        out[i] = glm::vec3(p);
    }
    return out;
}

Result<std::unique_ptr<CharacterGeometry>> CharacterGeometry::create(CharacterGeometryDesc desc) {
    const uint32_t J = static_cast<uint32_t>(desc.skeleton.joint_count());
    std::vector<std::string> problems;
    if (J == 0) problems.push_back("skeleton has no joints");
    // A type without muscles (a non-humanoid) may only use rigid-proxy and, with a mesh, skinned-mesh levels.
    if (desc.muscles.size() == 0) desc.muscles.joint_count = static_cast<int>(J);
    if (desc.muscles.joint_count != static_cast<int>(J))
        problems.push_back("muscle set was resolved for " + std::to_string(desc.muscles.joint_count) +
                           " joints, the skeleton has " + std::to_string(J));
    if (desc.rest_model.empty()) desc.rest_model = rest_model_matrices(desc.skeleton);
    if (desc.rest_model.size() != J) problems.push_back("rest_model needs one matrix per joint");
    for (const glm::mat4& m : desc.rest_model) {
        if (!finite_matrix(m) || std::abs(glm::determinant(m)) < 1e-12f) {
            problems.push_back("rest_model holds a non-finite or singular matrix");
            break;
        }
    }
    if (desc.mesh) check_mesh(*desc.mesh, J, problems);
    if (!(desc.length_scale > 0.0f) || !std::isfinite(desc.length_scale)) problems.push_back("length_scale must be positive and finite");
    if (!problems.empty()) {
        std::string message = "character type '" + desc.name + "': " + problems.front();
        for (size_t i = 1; i < problems.size(); ++i) message += "; " + problems[i];
        return make_error(desc.name, message);
    }

    std::unique_ptr<CharacterGeometry> g(new CharacterGeometry());
    g->type_ = desc.type;
    g->name_ = std::move(desc.name);
    g->skeleton_ = std::move(desc.skeleton);
    g->muscles_ = std::move(desc.muscles);
    g->rest_model_ = std::move(desc.rest_model);
    g->inverse_rest_.resize(J);
    for (size_t j = 0; j < J; ++j) g->inverse_rest_[j] = glm::inverse(g->rest_model_[j]);
    g->length_scale_ = desc.length_scale;
    g->proxy_radii_ = proxy_radii_of(g->skeleton_, g->muscles_, g->length_scale_);
    g->table_cache_ = std::make_unique<SuperEllipsoidTableCache>(g->muscles_);
    g->mesh_ = std::move(desc.mesh);
    if (g->mesh_) g->mesh_rest_positions_ = skin_mesh_positions(*g->mesh_, g->rest_model_);
    g->bake_cache_ = std::move(desc.bake_cache);
    if (g->bake_cache_ && !g->mesh_ && g->muscles_.size() > 0)
        g->bake_inputs_ = skin_bake_inputs(g->muscles_, g->skeleton_.parents(), g->rest_model_, g->proxy_radii_, g->length_scale_);
    return g;
}

const SuperEllipsoidTables& CharacterGeometry::tables(uint32_t theta_steps, uint32_t phi_steps) const {
    std::lock_guard lock(mutex_);
    return table_cache_->get(theta_steps, phi_steps);
}

const GeneratedBindMesh& CharacterGeometry::generated_mesh(uint32_t theta_steps, uint32_t phi_steps) const {
    const SuperEllipsoidTables& tab = tables(theta_steps, phi_steps);
    std::lock_guard lock(mutex_);
    auto& slot = generated_[{theta_steps, phi_steps}];
    if (!slot) slot = std::make_unique<GeneratedBindMesh>(build_generated_mesh(muscles_, skeleton_.parents(), rest_model_, tab));
    return *slot;
}

std::unique_ptr<SkinLayer> CharacterGeometry::cached_skin_layer(uint32_t theta_steps, uint32_t phi_steps) const {
    const BlobStore* cache = skin_layer_cache();
    if (!cache) return nullptr;
    const std::optional<std::vector<uint8_t>> bytes = cache->get(skin_layer_key(bake_inputs_, theta_steps, phi_steps));
    if (!bytes) return nullptr;
    std::optional<SkinLayer> layer = read_skin_layer(*bytes, muscle_count());
    if (!layer || layer->theta_steps != theta_steps || layer->phi_steps != phi_steps) return nullptr;
    return std::make_unique<SkinLayer>(std::move(*layer));
}

void CharacterGeometry::save_skin_layer(const SkinLayer& layer) const {
    if (const BlobStore* cache = skin_layer_cache()) cache->put(skin_layer_key(bake_inputs_, layer.theta_steps, layer.phi_steps), write_skin_layer(layer));
}

const SkinLayer& CharacterGeometry::skin_layer(uint32_t theta_steps, uint32_t phi_steps) const {
    assert(muscles_.size() > 0);
    if (skin_layer_cache()) {  // a cached layer needs neither the tables nor the grid mesh
        {
            std::lock_guard lock(mutex_);
            if (const auto it = skin_layers_.find({theta_steps, phi_steps}); it != skin_layers_.end() && it->second) return *it->second;
        }
        if (std::unique_ptr<SkinLayer> cached = cached_skin_layer(theta_steps, phi_steps)) {
            std::lock_guard lock(mutex_);
            auto& slot = skin_layers_[{theta_steps, phi_steps}];
            if (!slot) slot = std::move(cached);
            return *slot;
        }
    }
    const SuperEllipsoidTables& tab = tables(theta_steps, phi_steps);
    const GeneratedBindMesh* grid = mesh_ ? nullptr : &generated_mesh(theta_steps, phi_steps);
    std::lock_guard lock(mutex_);
    auto& slot = skin_layers_[{theta_steps, phi_steps}];
    if (slot) return *slot;
    if (mesh_) {
        slot = std::make_unique<SkinLayer>(
            build_mesh_skin(mesh_rest_positions_, mesh_->indices, muscles_, skeleton_.parents(), rest_model_, tab, length_scale_));
    } else {
        if (!body_surface_)
            body_surface_ = std::make_unique<BodySurface>(build_body_surface(muscles_, skeleton_, rest_model_, proxy_radii_, length_scale_));
        slot = std::make_unique<SkinLayer>(build_generated_skin(*body_surface_, muscles_, skeleton_.parents(), rest_model_, tab, *grid, length_scale_));
        save_skin_layer(*slot);
    }
    return *slot;
}

void CharacterGeometry::prepare_skin_layers(std::span<const std::pair<uint32_t, uint32_t>> tessellations) const {
    if (mesh_) return;  // an authored mesh is bound as it is: nothing shared between tessellations
    // Tables and grid meshes first (they take the lock themselves), then the missing layers in one pass.
    std::vector<std::pair<uint32_t, uint32_t>> missing;
    std::vector<const SuperEllipsoidTables*> tabs;
    std::vector<const GeneratedBindMesh*> grids;
    std::vector<uint32_t> targets;
    for (const auto& tp : tessellations) {
        if (std::find(missing.begin(), missing.end(), tp) != missing.end()) continue;
        {
            std::lock_guard lock(mutex_);
            if (skin_layers_.contains(tp)) continue;
        }
        if (std::unique_ptr<SkinLayer> cached = cached_skin_layer(tp.first, tp.second)) {
            std::lock_guard lock(mutex_);
            auto& slot = skin_layers_[tp];
            if (!slot) slot = std::move(cached);
            continue;
        }
        missing.push_back(tp);
        tabs.push_back(&tables(tp.first, tp.second));
        grids.push_back(&generated_mesh(tp.first, tp.second));
        targets.push_back(generated_skin_triangles(muscles_, *tabs.back()));
    }
    if (missing.empty()) return;
    std::lock_guard lock(mutex_);
    if (!body_surface_) body_surface_ = std::make_unique<BodySurface>(build_body_surface(muscles_, skeleton_, rest_model_, proxy_radii_, length_scale_));
    std::vector<TriangleSurface> skins = simplify_and_relax_all(body_surface_->dense, body_surface_->field, targets);
    for (size_t i = 0; i < missing.size(); ++i) {
        auto& slot = skin_layers_[missing[i]];
        if (!slot) {
            slot = std::make_unique<SkinLayer>(
                bind_generated_skin(std::move(skins[i]), muscles_, skeleton_.parents(), rest_model_, *tabs[i], *grids[i], length_scale_));
            save_skin_layer(*slot);
        }
    }
}

const SubdivisionTopology& CharacterGeometry::subdivision(uint32_t theta_steps, uint32_t phi_steps, uint32_t level) const {
    const std::span<const uint32_t> idx = mesh_ ? std::span<const uint32_t>(mesh_->indices) : skin_layer(theta_steps, phi_steps).indices;
    const uint32_t vertices = mesh_ ? static_cast<uint32_t>(mesh_->positions.size())
                                    : static_cast<uint32_t>(skin_layer(theta_steps, phi_steps).rest_positions.size());
    std::lock_guard lock(mutex_);
    auto& slot = subdivisions_[{mesh_ ? 0u : theta_steps, mesh_ ? 0u : phi_steps, level}];
    if (!slot) {
        GridFaces faces;
        faces.vertex_counts.assign(idx.size() / 3, 3);
        faces.vertex_indices.assign(idx.begin(), idx.end());
        slot = build_subdivision(faces, vertices, level);
    }
    return *slot;
}

const SurfaceMap& CharacterGeometry::skin_map(uint32_t from_theta, uint32_t from_phi, uint32_t to_theta, uint32_t to_phi) const {
    assert(!mesh_);
    return surface_map({from_theta, from_phi, 0}, {to_theta, to_phi, 0});
}

void CharacterGeometry::rest_surface(SkinSurfaceKey key, std::vector<glm::vec3>& positions, std::vector<uint32_t>& indices) const {
    if (mesh_) {
        positions = mesh_rest_positions_;
        indices = mesh_->indices;
    } else {
        const SkinLayer& skin = skin_layer(key.theta_steps, key.phi_steps);
        positions = skin.rest_positions;
        indices = skin.indices;
    }
    if (key.subdivision == 0) return;
    const SubdivisionTopology& refinement = subdivision(key.theta_steps, key.phi_steps, key.subdivision);
    std::vector<glm::vec3> refined(refinement.refined_vertex_count);
    const SubdivideJob refine{&refinement, positions, refined, {}};
    assert(refine.Validate());
    refine.Run();
    positions = std::move(refined);
    indices = refinement.triangles;
}

const SurfaceMap& CharacterGeometry::surface_map(SkinSurfaceKey from, SkinSurfaceKey to) const {
    if (mesh_) from.theta_steps = from.phi_steps = to.theta_steps = to.phi_steps = 0;  // one mesh at every (T, P)
    const std::pair key{from, to};
    {
        std::lock_guard lock(mutex_);
        if (const auto it = surface_maps_.find(key); it != surface_maps_.end()) return *it->second;
    }
    // Built outside the lock (the rest surfaces take it themselves); a racing builder's copy is dropped.
    // The bake cache keys a map by the surfaces themselves (skin_bake.hpp), so refined ones are cached too.
    std::vector<glm::vec3> source, target;
    std::vector<uint32_t> source_indices, target_indices;
    rest_surface(from, source, source_indices);
    rest_surface(to, target, target_indices);
    std::unique_ptr<SurfaceMap> map;
    const std::vector<uint8_t> bake_key = bake_cache_ ? surface_map_key(source, source_indices, target) : std::vector<uint8_t>{};
    if (bake_cache_)
        if (const auto bytes = bake_cache_->get(bake_key))
            if (std::optional<SurfaceMap> read = read_surface_map(*bytes, source.size(), target.size()))
                map = std::make_unique<SurfaceMap>(std::move(*read));
    if (!map) {
        map = std::make_unique<SurfaceMap>(map_surface(source, source_indices, target));
        if (bake_cache_) bake_cache_->put(bake_key, write_surface_map(*map));
    }
    std::lock_guard lock(mutex_);
    auto& slot = surface_maps_[key];
    if (!slot) slot = std::move(map);
    return *slot;
}

std::vector<uint32_t> CharacterGeometry::simplified(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                                   float target_error) const {
    if (!bake_cache_) return simplify_indices(positions, indices, target_error).indices;
    const std::vector<uint8_t> key = simplified_indices_key(positions, indices, target_error);
    if (const auto bytes = bake_cache_->get(key))
        if (std::optional<std::vector<uint32_t>> read = read_triangle_list(*bytes, positions.size())) return std::move(*read);
    std::vector<uint32_t> made = simplify_indices(positions, indices, target_error).indices;
    bake_cache_->put(key, write_triangle_list(made));
    return made;
}

void CharacterGeometry::prepare_surface_maps(std::span<const std::pair<SkinSurfaceKey, SkinSurfaceKey>> pairs) const {
    // Each map is independent and surface_map() builds outside the lock: one thread per map.
    std::vector<std::future<void>> built;
    for (const auto& [from, to] : pairs) {
        {
            std::lock_guard lock(mutex_);
            if (surface_maps_.contains({from, to})) continue;
        }
        built.push_back(std::async(std::launch::async, [this, from, to] { (void)surface_map(from, to); }));
    }
    for (auto& b : built) b.get();
}

}  // namespace aloha
