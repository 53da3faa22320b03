// `aloha export SCENE --frame N --character I [--level L] --out FILE.glb`: runs the scene headless (CPU
// systems only) to frame N and writes character I's displayed body at that frame as glTF 2.0 binary:
// one mesh in world space (the skin of its geometric level, or the boxes of its rigid proxy) and its
// skeleton as a node hierarchy at that frame's pose (nodes only, no glTF skin: the mesh is already
// deformed). Hidden and impostor levels draw no mesh and are refused, naming the level.
#include "host/scene/character_runtime.hpp"
#include "host/tool/commands.hpp"
#include "host/tool/session.hpp"
#include "systems/lod/rule_table.hpp"
#include "systems/lod/stats.hpp"

#include <tiny_gltf.h>

#include <cfloat>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace aloha::tool {

namespace {

// Appends `count` elements of `bytes` each from `data` to buffer 0 as a new buffer view; returns its index.
int add_view(tinygltf::Model& model, const void* data, size_t bytes, int target) {
    std::vector<unsigned char>& buffer = model.buffers[0].data;
    while (buffer.size() % 4) buffer.push_back(0);  // every view 4-byte aligned
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    buffer.resize(buffer.size() + bytes);
    std::memcpy(buffer.data() + view.byteOffset, data, bytes);
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size() - 1);
}

// An accessor over a whole buffer view.
int add_accessor(tinygltf::Model& model, int view, int component, int type, size_t count) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = component;
    a.type = type;
    a.count = count;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size() - 1);
}

std::vector<double> matrix_values(const glm::mat4& m) {
    std::vector<double> v(16);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) v[static_cast<size_t>(c * 4 + r)] = static_cast<double>(m[c][r]);  // column-major, as glTF
    return v;
}

// The glTF document of one character's sample: node 0 the mesh, node 1 the placement, nodes 2.. the joints.
tinygltf::Model skin_document(const SkinSample& s, const std::string& name) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "aloha export";
    model.buffers.emplace_back();
    std::vector<glm::vec3> normals = s.normals;
    for (glm::vec3& n : normals) n = glm::dot(n, n) > 1e-12f ? glm::normalize(n) : glm::vec3(0.0f, 1.0f, 0.0f);
    const int positions = add_accessor(model, add_view(model, s.positions.data(), s.positions.size() * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER),
                                       TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, s.positions.size());
    glm::vec3 lo(FLT_MAX), hi(-FLT_MAX);
    for (const glm::vec3& p : s.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    model.accessors[static_cast<size_t>(positions)].minValues = {lo.x, lo.y, lo.z};
    model.accessors[static_cast<size_t>(positions)].maxValues = {hi.x, hi.y, hi.z};
    const int normal = add_accessor(model, add_view(model, normals.data(), normals.size() * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER),
                                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size());
    const int indices = add_accessor(model, add_view(model, s.indices.data(), s.indices.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, s.indices.size());
    model.buffers[0].data.resize((model.buffers[0].data.size() + 3) / 4 * 4, 0);
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = positions;
    primitive.attributes["NORMAL"] = normal;
    primitive.indices = indices;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);

    tinygltf::Node skin_node;
    skin_node.name = name + " skin";
    skin_node.mesh = 0;
    tinygltf::Node placement;
    placement.name = name + " placement";
    placement.matrix = matrix_values(s.placement);
    model.nodes.push_back(skin_node);
    model.nodes.push_back(placement);
    const glm::mat4 unplace = glm::inverse(s.placement);
    for (size_t j = 0; j < s.joints.size(); ++j) {
        tinygltf::Node joint;
        joint.name = j < s.joint_names.size() ? s.joint_names[j] : "joint " + std::to_string(j);
        const int16_t parent = s.parents[j];
        joint.matrix = matrix_values((parent < 0 ? unplace : glm::inverse(s.joints[static_cast<size_t>(parent)])) * s.joints[j]);
        model.nodes.push_back(joint);
        model.nodes[parent < 0 ? 1 : static_cast<size_t>(parent) + 2].children.push_back(static_cast<int>(j + 2));
    }
    tinygltf::Scene scene;
    scene.name = name;
    scene.nodes = {0, 1};
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    return model;
}

// The type and id of spawn index `index` (types in scene order, then id).
size_t type_of(const World& world, uint32_t index) {
    size_t t = 0;
    for (uint32_t first = 0; t + 1 < world.type_count() && index >= first + world.runtime(t).count; ++t) first += world.runtime(t).count;
    return t;
}

// "0 'hero' (subdivided), 1 'near' (layered), ...": the levels that draw something for type `t`.
std::string drawn_levels(const World& world, size_t t) {
    const RuleTable& table = world.rules().table();
    const GeometryController& gc = *world.runtime(t).geometry;
    std::string out;
    for (uint8_t l = 0; l < gc.level_count(); ++l) {
        const GeomMethod m = gc.level(l).method;
        if (m == GeomMethod::Hidden || m == GeomMethod::Impostor) continue;
        out += (out.empty() ? "" : ", ") + std::to_string(l) + " '" + table.geom_levels[l].name + "' (" + std::string(to_string(m)) + ")";
    }
    return out;
}

// Empty when level `l` of type `t` draws a mesh or boxes; else why not (named by `what`).
std::string no_mesh_reason(const World& world, size_t t, uint8_t l, const std::string& what) {
    const GeomMethod m = world.runtime(t).geometry->level(l).method;
    if (m != GeomMethod::Hidden && m != GeomMethod::Impostor) return {};
    const std::string name = "level " + std::to_string(l) + " '" + world.rules().table().geom_levels[l].name + "'";
    return what + " " + name + (m == GeomMethod::Hidden ? " is hidden: it draws nothing" : " is an impostor: it draws a pre-rendered picture, not a mesh") +
           "; levels with a mesh: " + drawn_levels(world, t);
}

}  // namespace

int export_skin(const CliOptions& options, Session& s) {
    World& world = *s.world;
    const uint32_t frame = *options.frame, character = *options.character;
    const size_t count = world.character_count(), levels = world.rules().table().geom_levels.size();
    if (character >= count) {
        print_error("--character " + std::to_string(character) + " is past the crowd: " + options.scene + " has " + std::to_string(count) +
                    " characters (0 to " + std::to_string(count - 1) + ")");
        return 2;
    }
    if (frame >= s.scene.frames) {
        print_error("--frame " + std::to_string(frame) + " is past the scene: " + options.scene + " runs " + std::to_string(s.scene.frames) +
                    " frames (0 to " + std::to_string(s.scene.frames - 1) + ")");
        return 2;
    }
    const size_t t = type_of(world, character);
    if (options.level) {
        if (*options.level >= levels) {
            print_error("--level " + std::to_string(*options.level) + " is past the rule table's geometric levels: " +
                        world.rules().table().source + " has " + std::to_string(levels) + " (0 to " + std::to_string(levels - 1) + ")");
            return 2;
        }
        const auto level = static_cast<uint8_t>(*options.level);
        if (const std::string why = no_mesh_reason(world, t, level, "--level"); !why.empty()) return print_error(why), 2;
        if (Status st = world.pin_geom_level(character, level); !st.ok()) return print_error(st.error().to_string()), 2;
    }
    for (uint32_t f = 0; f <= frame; ++f) world.step();
    SkinSample sample;
    world.skin_sample(character, sample);
    if (sample.level == GeometryController::kNoLevel) return print_error("character " + std::to_string(character) + " has no level"), 1;
    if (const std::string why = no_mesh_reason(world, t, sample.level, "at frame " + std::to_string(frame) + " character " +
                                                                          std::to_string(character) + " is at");
        !why.empty())
        return print_error(why + " (pass --level L to hold it at one of them)"), 2;
    if (options.level && sample.level != *options.level) {
        print_error("character " + std::to_string(character) + " could not be held at --level " + std::to_string(*options.level) +
                    " (it is at level " + std::to_string(sample.level) + ")");
        return 1;
    }
    if (sample.positions.empty() || sample.indices.empty()) return print_error("character " + std::to_string(character) + " has no surface yet"), 1;
    const std::string name = world.type(sample.type).name + " " + std::to_string(sample.id) + " level " + std::to_string(sample.level) +
                             " frame " + std::to_string(frame);
    const tinygltf::Model model = skin_document(sample, name);
    // Written beside the target and renamed at the end: a failed run leaves nothing half-written.
    const std::string partial = options.out + ".partial";
    tinygltf::TinyGLTF writer;
    std::error_code ec;
    if (!writer.WriteGltfSceneToFile(&model, partial, /*embedImages=*/false, /*embedBuffers=*/true, /*prettyPrint=*/false,
                                     /*writeBinary=*/true) ||
        (std::filesystem::rename(partial, options.out, ec), ec)) {
        std::filesystem::remove(partial, ec);
        print_error("cannot write " + options.out);
        return 1;
    }
    std::cout << "exported character " << character << " (" << name << ", " << std::string(to_string(sample.method)) << "): "
              << sample.positions.size() << " vertices, " << sample.indices.size() / 3 << " triangles, " << sample.joints.size()
              << " joints, to " << options.out << "\n";
    return 0;
}

}  // namespace aloha::tool
