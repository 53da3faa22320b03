// Characters without a skin: a glTF whose meshes hang rigidly on an animated node hierarchy (a robot or a
// segmented figure, as CAD and older game pipelines export them) gets a skin of its own before the skins
// are read: every node of the displayed scene becomes a joint, bound at its rest pose, so each mesh is a
// rigid part of its node and the node animations are the clips.
#include "engine/assets/gltf_detail.hpp"

#include <cmath>
#include <cstring>

namespace aloha::gltf_detail {

namespace {

// The nodes of the scene the file displays (its `scene`, else scenes[0], else every root node), parents
// before children, with their rest world matrices.
Status scene_nodes(const tinygltf::Model& model, const std::vector<int>& parents, const std::string& file, std::vector<int>* nodes,
                   std::vector<glm::mat4>* world) {
    std::vector<int> roots;
    const int scene = model.defaultScene >= 0 ? model.defaultScene : (model.scenes.empty() ? -1 : 0);
    if (scene >= 0 && static_cast<size_t>(scene) < model.scenes.size()) {
        roots = model.scenes[static_cast<size_t>(scene)].nodes;
    } else {
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (parents[i] < 0) roots.push_back(static_cast<int>(i));
    }
    std::vector<int> stack(roots.rbegin(), roots.rend());
    std::vector<glm::mat4> world_of(model.nodes.size(), glm::mat4(1.0f));
    std::vector<uint8_t> seen(model.nodes.size(), 0), known(model.nodes.size(), 0);
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        if (n < 0 || static_cast<size_t>(n) >= model.nodes.size())
            return make_error(file, "node " + std::to_string(n) + " is out of range (the file has " + std::to_string(model.nodes.size()) + " nodes)", 0, 0,
                              "scenes[" + std::to_string(scene) + "].nodes");
        if (seen[static_cast<size_t>(n)]) continue;  // listed twice: node_parents() reports real cycles
        seen[static_cast<size_t>(n)] = 1;
        // The world matrix through every ancestor (a scene may list a node that has a parent): up to the nearest
        // ancestor already known, then down; each node is computed once.
        std::vector<int> chain;
        for (int a = n; a >= 0 && !known[static_cast<size_t>(a)]; a = parents[static_cast<size_t>(a)]) chain.push_back(a);
        for (auto a = chain.rbegin(); a != chain.rend(); ++a) {
            Result<glm::mat4> local = node_local_matrix(model, *a, file);
            if (!local.ok()) return local.error();
            const int p = parents[static_cast<size_t>(*a)];
            world_of[static_cast<size_t>(*a)] = (p >= 0 ? world_of[static_cast<size_t>(p)] : glm::mat4(1.0f)) * local.value();
            known[static_cast<size_t>(*a)] = 1;
        }
        nodes->push_back(n);
        world->push_back(world_of[static_cast<size_t>(n)]);
        const std::vector<int>& children = model.nodes[static_cast<size_t>(n)].children;
        for (auto c = children.rbegin(); c != children.rend(); ++c) stack.push_back(*c);
    }
    return {};
}

}  // namespace

Status add_node_skin(tinygltf::Model* model, const std::vector<int>& parents, const std::string& file, std::vector<std::string>* notes) {
    if (!model->skins.empty()) return {};
    bool meshes = false;
    for (const tinygltf::Node& node : model->nodes) meshes |= node.mesh >= 0;
    if (!meshes && model->animations.empty()) return {};  // nothing to draw or play: read_skins says the file has no skins
    std::vector<int> nodes;
    std::vector<glm::mat4> world;
    if (Status s = scene_nodes(*model, parents, file, &nodes, &world); !s.ok()) return s;
    if (nodes.empty()) return {};
    if (nodes.size() > 32767)
        return make_error(file, "a file without skins is drawn with its " + std::to_string(nodes.size()) +
                                    " scene nodes as joints; at most 32767 are supported", 0, 0, "nodes");
    // Inverse bind matrices (the rest world matrix of each node, inverted) in a buffer of their own.
    tinygltf::Buffer buffer;
    buffer.data.resize(nodes.size() * sizeof(glm::mat4));
    for (size_t i = 0; i < nodes.size(); ++i) {
        const float det = glm::determinant(glm::mat3(world[i]));
        if (!(std::abs(det) > 1e-24f))
            return make_error(file, "the node's rest transform is singular (zero scale); a file without skins uses its nodes as joints", 0, 0,
                              "nodes[" + std::to_string(nodes[i]) + "]");
        const glm::mat4 ibm = glm::inverse(world[i]);
        std::memcpy(buffer.data.data() + i * sizeof(glm::mat4), &ibm[0][0], sizeof(glm::mat4));
    }
    tinygltf::BufferView view;
    view.buffer = static_cast<int>(model->buffers.size());
    view.byteLength = buffer.data.size();
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model->bufferViews.size());
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = TINYGLTF_TYPE_MAT4;
    accessor.count = nodes.size();
    model->buffers.push_back(std::move(buffer));
    model->bufferViews.push_back(view);
    tinygltf::Skin skin;
    skin.name = "scene nodes";
    skin.joints = nodes;
    skin.inverseBindMatrices = static_cast<int>(model->accessors.size());
    model->accessors.push_back(accessor);
    model->skins.push_back(std::move(skin));
    notes->push_back(meshes ? "no skin: the " + std::to_string(nodes.size()) + " nodes of the scene are the skeleton, each mesh a rigid part of its node"
                            : "no skin and no mesh (an animation file): the " + std::to_string(nodes.size()) +
                                  " nodes of the scene are the skeleton, its animations the clips");
    return {};
}

}  // namespace aloha::gltf_detail
