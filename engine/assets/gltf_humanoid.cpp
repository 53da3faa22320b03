// The humanoid a glTF file declares for itself: VRM's humanoid bones (VRM 1.0's VRMC_vrm extension,
// VRM 0.x's VRM extension), which name the node of each bone whatever the nodes are called. Read
// into GltfCharacter::humanoid (canonical joint name -> joint name), which map_humanoid puts above
// the naming conventions and below a scene's humanoid_map.
#include "engine/assets/gltf_detail.hpp"

#include <map>
#include <set>

namespace aloha::gltf_detail {

namespace {

// One declared bone: its VRM name, its node, and where it sits in the file (for errors).
struct DeclaredBone {
    std::string bone;
    int64_t node = -1;      // -1 also for a node that is no index (an error unless `unassigned`)
    bool unassigned = false;  // "node": -1, as Unity-based exporters write a bone the avatar lacks
    std::string at;
};

DeclaredBone declared(const std::string& bone, const tinygltf::Value& node, const std::string& at) {
    return {bone, non_negative_integer(node), node.IsNumber() && node.GetNumberAsDouble() == -1.0, at};
}

// The VRM 1.0 form: humanoid.humanBones is an object of bone name -> {"node": index}.
Status read_vrm1(const tinygltf::Value& bones, const std::string& at, const std::string& file, std::vector<DeclaredBone>* out) {
    if (!bones.IsObject()) return make_error(file, "expected an object of bone name -> {\"node\": index}", 0, 0, at);
    for (const std::string& name : bones.Keys()) {
        const tinygltf::Value& entry = bones.Get(name);
        const std::string here = at + "." + name;
        if (!entry.IsObject() || !entry.Has("node"))
            return make_error(file, "expected an object with a 'node' index", 0, 0, here);
        out->push_back(declared(name, entry.Get("node"), here + ".node"));
    }
    return {};
}

// The VRM 0.x form: humanoid.humanBones is an array of {"bone": name, "node": index}.
Status read_vrm0(const tinygltf::Value& bones, const std::string& at, const std::string& file, std::vector<DeclaredBone>* out) {
    if (!bones.IsArray()) return make_error(file, "expected an array of {\"bone\": name, \"node\": index}", 0, 0, at);
    for (size_t i = 0; i < bones.ArrayLen(); ++i) {
        const tinygltf::Value& entry = bones.Get(static_cast<int>(i));
        const std::string here = at + "[" + std::to_string(i) + "]";
        if (!entry.IsObject() || !entry.Has("bone") || !entry.Get("bone").IsString() || !entry.Has("node"))
            return make_error(file, "expected an object with a 'bone' name and a 'node' index", 0, 0, here);
        out->push_back(declared(entry.Get("bone").Get<std::string>(), entry.Get("node"), here + ".node"));
    }
    return {};
}

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

}  // namespace

Status read_declared_humanoid(const tinygltf::Model& model, const SkinSet& skins, const std::string& file, GltfCharacter* out) {
    const bool vrm1 = model.extensions.count("VRMC_vrm") > 0;
    const char* extension = vrm1 ? "VRMC_vrm" : "VRM";
    const auto found = model.extensions.find(extension);
    if (found == model.extensions.end()) return {};
    const std::string origin = vrm1 ? "VRM 1.0 humanoid" : "VRM 0.x humanoid";
    const std::string at = std::string("extensions.") + extension + ".humanoid";
    const tinygltf::Value& root = found->second;
    if (!root.IsObject() || !root.Has("humanoid") || !root.Get("humanoid").IsObject() || !root.Get("humanoid").Has("humanBones"))
        return make_error(file, "the " + std::string(extension) + " extension has no humanoid.humanBones (a VRM file declares its humanoid bones there)", 0, 0,
                          std::string("extensions.") + extension);
    std::vector<DeclaredBone> bones;
    const tinygltf::Value& list = root.Get("humanoid").Get("humanBones");
    if (Status s = vrm1 ? read_vrm1(list, at + ".humanBones", file, &bones) : read_vrm0(list, at + ".humanBones", file, &bones); !s.ok())
        return s;

    std::map<std::string, std::string> joints;     // canonical -> joint name
    std::map<int64_t, std::string> bone_of_node;   // one bone per node, as VRM requires
    std::set<std::string> seen;
    std::vector<std::string> not_joints, not_canonical, unassigned;
    for (const DeclaredBone& b : bones) {
        if (b.unassigned) {
            unassigned.push_back(b.bone);
            continue;
        }
        if (b.node < 0 || b.node >= static_cast<int64_t>(model.nodes.size()))
            return make_error(file, "bone '" + b.bone + "': expected a node index 0-" + std::to_string(model.nodes.size() - 1), 0, 0, b.at);
        if (!seen.insert(b.bone).second) return make_error(file, "bone '" + b.bone + "' is declared twice", 0, 0, b.at);
        if (const auto other = bone_of_node.find(b.node); other != bone_of_node.end())
            return make_error(file, "nodes[" + std::to_string(b.node) + "] is declared for both '" + other->second + "' and '" + b.bone + "'", 0, 0, b.at);
        bone_of_node[b.node] = b.bone;
        const int raw = skins.joint_of_node[static_cast<size_t>(b.node)];
        const std::string canonical = canonical_of_humanoid_bone(b.bone, vrm1);
        if (canonical.empty()) {
            not_canonical.push_back(b.bone);
            continue;
        }
        if (raw < 0) {
            not_joints.push_back(b.bone + " (nodes[" + std::to_string(b.node) + "])");
            continue;
        }
        joints[canonical] = out->skeleton.joints[static_cast<size_t>(raw)].name;
    }
    out->humanoid.origin = origin;
    out->humanoid.joints = std::move(joints);
    out->notes.push_back(origin + ": " + std::to_string(bones.size()) + " bone" + (bones.size() == 1 ? "" : "s") + " declared, " +
                         std::to_string(out->humanoid.joints.size()) + " of them canonical joints used by the layers" +
                         (not_canonical.empty() ? "" : " (not canonical, carried along: " + joined(not_canonical) + ")"));
    if (!not_joints.empty())
        out->notes.push_back(origin + ": bones on nodes that are no skin's joints, left to the naming conventions: " + joined(not_joints));
    if (!unassigned.empty()) out->notes.push_back(origin + ": bones declared without a node (-1), ignored: " + joined(unassigned));
    return {};
}

}  // namespace aloha::gltf_detail
