// OpenSubdiv refinement cache and per-frame stencil evaluation.
#include "systems/geometry/spring_skin/subdivision.hpp"

#include "systems/geometry/spring_skin/skin_mesh.hpp"

#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cassert>

namespace aloha {

namespace osd = OpenSubdiv::Far;
namespace sdc = OpenSubdiv::Sdc;

std::unique_ptr<SubdivisionTopology> build_subdivision(const GridFaces& faces, uint32_t vertex_count, uint32_t level) {
    assert(level <= 4);
    auto topo = std::make_unique<SubdivisionTopology>();
    topo->control_vertex_count = vertex_count;
    if (level == 0) {  // identity stencils, faces triangulated as they are
        topo->refined_vertex_count = vertex_count;
        topo->refined_face_count = static_cast<uint32_t>(faces.vertex_counts.size());
        for (uint32_t i = 0; i <= vertex_count; ++i) topo->offsets.push_back(i);
        for (uint32_t i = 0; i < vertex_count; ++i) {
            topo->indices.push_back(i);
            topo->weights.push_back(1.0f);
        }
        size_t at = 0;
        for (int count : faces.vertex_counts) {
            for (int k = 1; k + 1 < count; ++k) {
                topo->triangles.insert(topo->triangles.end(),
                                       {static_cast<uint32_t>(faces.vertex_indices[at]),
                                        static_cast<uint32_t>(faces.vertex_indices[at + static_cast<size_t>(k)]),
                                        static_cast<uint32_t>(faces.vertex_indices[at + static_cast<size_t>(k) + 1])});
            }
            at += static_cast<size_t>(count);
        }
        return topo;
    }

    osd::TopologyDescriptor desc;
    desc.numVertices = static_cast<int>(vertex_count);
    desc.numFaces = static_cast<int>(faces.vertex_counts.size());
    desc.numVertsPerFace = faces.vertex_counts.data();
    desc.vertIndicesPerFace = faces.vertex_indices.data();
    sdc::Options sdc_options;
    sdc_options.SetVtxBoundaryInterpolation(sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    using Factory = osd::TopologyRefinerFactory<osd::TopologyDescriptor>;
    std::unique_ptr<osd::TopologyRefiner> refiner(
        Factory::Create(desc, Factory::Options(sdc::SCHEME_CATMARK, sdc_options)));
    assert(refiner && "grid topology is always valid for OpenSubdiv");
    refiner->RefineUniform(osd::TopologyRefiner::UniformOptions(static_cast<int>(level)));

    osd::StencilTableFactory::Options stencil_options;
    stencil_options.generateIntermediateLevels = false;  // finest level only
    stencil_options.generateOffsets = true;
    std::unique_ptr<const osd::StencilTable> stencils(osd::StencilTableFactory::Create(*refiner, stencil_options));

    const osd::TopologyLevel& finest = refiner->GetLevel(static_cast<int>(level));
    topo->refined_vertex_count = static_cast<uint32_t>(stencils->GetNumStencils());
    assert(topo->refined_vertex_count == static_cast<uint32_t>(finest.GetNumVertices()));
    topo->offsets.reserve(topo->refined_vertex_count + 1);
    const std::vector<int>& sizes = stencils->GetSizes();
    const std::vector<osd::Index>& offsets = stencils->GetOffsets();
    const std::vector<osd::Index>& control = stencils->GetControlIndices();
    const std::vector<float>& weights = stencils->GetWeights();
    for (uint32_t i = 0; i < topo->refined_vertex_count; ++i) {
        topo->offsets.push_back(static_cast<uint32_t>(topo->indices.size()));
        for (int k = 0; k < sizes[i]; ++k) {
            const size_t at = static_cast<size_t>(offsets[i]) + static_cast<size_t>(k);
            topo->indices.push_back(static_cast<uint32_t>(control[at]));
            topo->weights.push_back(weights[at]);
        }
    }
    topo->offsets.push_back(static_cast<uint32_t>(topo->indices.size()));

    topo->refined_face_count = static_cast<uint32_t>(finest.GetNumFaces());
    topo->triangles.reserve(static_cast<size_t>(topo->refined_face_count) * 6);
    for (int f = 0; f < finest.GetNumFaces(); ++f) {
        const osd::ConstIndexArray fv = finest.GetFaceVertices(f);
        for (int k = 1; k + 1 < fv.size(); ++k) {
            topo->triangles.insert(topo->triangles.end(), {static_cast<uint32_t>(fv[0]), static_cast<uint32_t>(fv[k]),
                                                           static_cast<uint32_t>(fv[k + 1])});
        }
    }
    return topo;
}

const SubdivisionTopology& SubdivisionCache::get(const SubdivisionKey& key) {
    assert(key.theta_steps >= 3 && key.phi_steps >= 2 && key.muscle_count >= 1 && key.level <= 4);
    std::lock_guard lock(mutex_);
    auto it = entries_.find(key);
    if (it != entries_.end()) return *it->second;
    GridFaces faces;
    const uint32_t V = grid_vertex_count(key.theta_steps, key.phi_steps);
    for (uint32_t m = 0; m < key.muscle_count; ++m)
        append_grid_faces(key.theta_steps, key.phi_steps, static_cast<int>(m * V), faces);
    ++builds_;
    auto [inserted, ok] = entries_.emplace(key, build_subdivision(faces, V * key.muscle_count, key.level));
    (void)ok;
    return *inserted->second;
}

size_t SubdivisionCache::build_count() const {
    std::lock_guard lock(mutex_);
    return builds_;
}

bool SubdivideJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("SubdivideJob: " + std::move(message));
    };
    if (topology == nullptr) {
        fail("topology is null");
        return false;
    }
    const size_t cv = topology->control_vertex_count, rv = topology->refined_vertex_count;
    if (cv == 0 || control_positions.size() % cv != 0) fail("control_positions is not a whole number of control meshes");
    const size_t characters = cv == 0 ? 0 : control_positions.size() / cv;
    if (refined_positions.size() != characters * rv) fail("refined_positions must hold refined_vertex_count per character");
    if (!refined_normals.empty() && refined_normals.size() != refined_positions.size())
        fail("refined_normals must be empty or the size of refined_positions");
    return ok;
}

void SubdivideJob::Run() const {
    assert(Validate());
    const SubdivisionTopology& t = *topology;
    const size_t cv = t.control_vertex_count, rv = t.refined_vertex_count;
    const size_t characters = control_positions.size() / cv;
    for (size_t c = 0; c < characters; ++c) {
        const glm::vec3* control = control_positions.data() + c * cv;
        glm::vec3* out = refined_positions.data() + c * rv;
        for (size_t i = 0; i < rv; ++i) {
            glm::vec3 sum(0.0f);
            for (uint32_t k = t.offsets[i]; k < t.offsets[i + 1]; ++k) sum += t.weights[k] * control[t.indices[k]];
            out[i] = sum;
        }
        if (!refined_normals.empty())
            accumulate_vertex_normals(refined_positions.subspan(c * rv, rv), t.triangles, refined_normals.subspan(c * rv, rv));
    }
}

}  // namespace aloha
