// Test helper: project-written humanoid rigs in other tools' conventions, generated from the
// built-in humanoid's proportions (data/characters/humanoid.json): renamed joints (a canonical
// joint left out of the table is dropped, its children re-parented), extra joints, a T-pose,
// units, a Z-up or turned frame, per-joint rest rotations (bones along local +Y as Blender and most
// glTF exporters write them), and writers for BVH and glTF text files with a short clip.
#pragma once

#include "engine/anim/raw_skeleton.hpp"
#include "engine/anim/rest_pose.hpp"
#include "engine/assets/humanoid_definition.hpp"
#include "tests/common/test_humanoid.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace aloha::test {

/// A joint added to a fixture: `parent` names a joint of the fixture (file name).
struct ExtraJoint {
    std::string name;
    std::string parent;
    glm::vec3 offset;  ///< metres, canonical axes (+X left, +Y up, +Z forward)
};

/// How a fixture is written.
struct RigStyle {
    float units_per_metre = 1.0f;              ///< 100 = centimetres
    glm::quat axes{1, 0, 0, 0};                ///< file model = axes * canonical model (rotate to Z-up etc.)
    bool t_pose = false;                       ///< arms straight out sideways
    bool bone_frames = false;                  ///< rest rotations turning local +Y along each bone
};

/// A model-space skeleton (canonical axes, metres) renamed by `names` (canonical -> file name);
/// canonical joints not in `names` are dropped; `extras` are added.
inline RawSkeleton renamed_humanoid(const std::map<std::string, std::string>& names, const std::vector<ExtraJoint>& extras = {},
                                    bool t_pose = false) {
    const Skeleton h = humanoid_skeleton_for(HumanoidBody{1.75f, 0.5f});
    std::vector<glm::mat4> model = skeleton_rest_model(h);
    std::vector<glm::vec3> pos(model.size());
    for (size_t j = 0; j < model.size(); ++j) pos[j] = glm::vec3(model[j][3]);
    if (t_pose)
        for (const char* side : {"Left", "Right"}) {
            const int sh = h.find(std::string(side) + "Shoulder");
            const glm::vec3 s = pos[static_cast<size_t>(sh)];
            // Every joint below the shoulder: turn the arm (hanging along -Y) out to +-X.
            const glm::quat up = glm::angleAxis(side[0] == 'L' ? 1.5707963f : -1.5707963f, glm::vec3(0, 0, 1));
            for (int j = 0; j < h.joint_count(); ++j) {
                bool below = false;
                for (int p = h.parents()[static_cast<size_t>(j)]; p >= 0; p = h.parents()[static_cast<size_t>(p)]) below |= p == sh;
                if (below) pos[static_cast<size_t>(j)] = s + up * (pos[static_cast<size_t>(j)] - s);
            }
        }
    RawSkeleton raw;
    std::vector<int> index_of(static_cast<size_t>(h.joint_count()), -1);
    std::vector<glm::vec3> model_pos;
    for (int j = 0; j < h.joint_count(); ++j) {
        const std::string canonical = h.names()[static_cast<size_t>(j)];
        const auto it = names.find(canonical);
        if (it == names.end()) continue;
        int p = h.parents()[static_cast<size_t>(j)];
        while (p >= 0 && index_of[static_cast<size_t>(p)] < 0) p = h.parents()[static_cast<size_t>(p)];
        RawJoint rj;
        rj.name = it->second;
        rj.parent = p < 0 ? -1 : index_of[static_cast<size_t>(p)];
        rj.translation = pos[static_cast<size_t>(j)] - (p < 0 ? glm::vec3(0.0f) : pos[static_cast<size_t>(p)]);
        index_of[static_cast<size_t>(j)] = static_cast<int>(raw.joints.size());
        raw.joints.push_back(rj);
        model_pos.push_back(pos[static_cast<size_t>(j)]);
    }
    for (const ExtraJoint& e : extras) {
        RawJoint rj;
        rj.name = e.name;
        for (size_t k = 0; k < raw.joints.size(); ++k)
            if (raw.joints[k].name == e.parent) rj.parent = static_cast<int>(k);
        EXPECT_GE(rj.parent, 0) << "extra joint parent " << e.parent;
        rj.translation = e.offset;
        raw.joints.push_back(rj);
    }
    return raw;
}

/// Inserts joint `name` between `child` and its parent, `fraction` of the way along the bone
/// (a twist bone: DAZ's lThighTwist between lThighBend and lShin). Requires model-aligned `raw`.
inline void insert_between(RawSkeleton& raw, const std::string& child, const std::string& name, float fraction) {
    for (size_t c = 0; c < raw.joints.size(); ++c) {
        if (raw.joints[c].name != child) continue;
        RawJoint twist;
        twist.name = name;
        twist.parent = raw.joints[c].parent;
        twist.translation = fraction * raw.joints[c].translation;
        raw.joints[c].translation -= twist.translation;
        raw.joints[c].parent = static_cast<int>(raw.joints.size());
        raw.joints.push_back(twist);  // after its children in file order: build_skeleton reorders
        return;
    }
    ADD_FAILURE() << "no joint " << child;
}

/// `raw` (model-aligned, metres, canonical axes) written in `style`: positions scaled and turned
/// by the axes, and with bone_frames local rest rotations (translations re-expressed in them).
inline RawSkeleton styled(const RawSkeleton& raw, const RigStyle& style) {
    const size_t n = raw.joints.size();
    // Without bone frames every joint frame is the file's model frame (BVH-like): offsets are
    // simply turned by the axes.
    std::vector<glm::quat> frame(n, style.bone_frames ? style.axes : glm::quat(1, 0, 0, 0));
    if (style.bone_frames)
        for (size_t j = 0; j < n; ++j)
            for (size_t c = j + 1; c < n; ++c)
                if (raw.joints[c].parent == static_cast<int>(j) && glm::length(raw.joints[c].translation) > 1e-4f) {
                    frame[j] = style.axes * rotation_between(glm::vec3(0, 1, 0), glm::normalize(raw.joints[c].translation));
                    break;
                }
    RawSkeleton out = raw;
    for (size_t j = 0; j < n; ++j) {
        const int p = raw.joints[j].parent;
        const glm::quat parent_frame = p < 0 ? glm::quat(1, 0, 0, 0) : frame[static_cast<size_t>(p)];
        const glm::vec3 file_offset = style.units_per_metre * (style.axes * raw.joints[j].translation);
        out.joints[j].translation = glm::inverse(parent_frame) * file_offset;
        out.joints[j].rotation = glm::normalize(glm::inverse(parent_frame) * frame[j]);
    }
    return out;
}

/// BVH text of a model-aligned `raw` (no rest rotations): every joint ZXY rotation channels, the
/// root also positions; leaves get an End Site. The clip: `frames` frames at 30 fps, the root
/// moving `step` file units per frame along `forward` (file axes) and every joint at rest.
inline std::string bvh_text(const RawSkeleton& raw, int frames, glm::vec3 forward, float step) {
    std::ostringstream s;
    s << "HIERARCHY\n";
    std::vector<std::vector<int>> children(raw.joints.size());
    for (size_t j = 1; j < raw.joints.size(); ++j) children[static_cast<size_t>(raw.joints[j].parent)].push_back(static_cast<int>(j));
    std::vector<int> order;
    auto write = [&](auto&& self, int j, int depth) -> void {
        const std::string pad(static_cast<size_t>(depth), '\t');
        const RawJoint& rj = raw.joints[static_cast<size_t>(j)];
        order.push_back(j);
        s << pad << (depth == 0 ? "ROOT " : "JOINT ") << rj.name << "\n" << pad << "{\n";
        s << pad << "\tOFFSET " << rj.translation.x << " " << rj.translation.y << " " << rj.translation.z << "\n";
        s << pad << "\tCHANNELS " << (depth == 0 ? "6 Xposition Yposition Zposition " : "3 ") << "Zrotation Xrotation Yrotation\n";
        for (int c : children[static_cast<size_t>(j)]) self(self, c, depth + 1);
        if (children[static_cast<size_t>(j)].empty()) s << pad << "\tEnd Site\n" << pad << "\t{\n" << pad << "\t\tOFFSET 0 0 0\n" << pad << "\t}\n";
        s << pad << "}\n";
    };
    write(write, 0, 0);
    s << "MOTION\nFrames: " << frames << "\nFrame Time: 0.0333333\n";
    for (int f = 0; f < frames; ++f) {
        const glm::vec3 root = raw.joints[0].translation + forward * (step * static_cast<float>(f));
        s << root.x << " " << root.y << " " << root.z;
        for (size_t k = 0; k < order.size(); ++k) s << " 0 0 0";
        s << "\n";
    }
    return s.str();
}

/// glTF JSON text of `raw` (rest rotations kept as node rotations): one node per joint, a skin
/// over all of them, and a clip "sway" of two keys turning joint `animated` by `angle` radians about
/// its local X. With `mesh`: a skinned triangle at every joint (each vertex bound to that joint,
/// inverse bind matrices from the rest pose) on a mesh node; without: no meshes and no inverse
/// bind matrices.
inline std::string gltf_text(const RawSkeleton& raw, int animated, float angle, bool mesh = false) {
    using nlohmann::json;
    std::string bytes;
    json views = json::array(), accessors = json::array();
    auto add = [&](const void* data, size_t size, int component, const char* type, size_t count, json extra = json::object()) {
        while (bytes.size() % 4) bytes += '\0';
        views.push_back({{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}});
        bytes.append(static_cast<const char*>(data), size);
        json a = {{"bufferView", views.size() - 1}, {"componentType", component}, {"count", count}, {"type", type}};
        a.update(extra);
        accessors.push_back(a);
        return static_cast<int>(accessors.size()) - 1;
    };
    json j;
    j["asset"] = {{"version", "2.0"}, {"generator", "aloha tests/common/rig_fixtures.hpp"}};
    j["scene"] = 0;
    json nodes = json::array();
    for (size_t k = 0; k < raw.joints.size(); ++k) {
        const RawJoint& rj = raw.joints[k];
        json node = {{"name", rj.name},
                     {"translation", {rj.translation.x, rj.translation.y, rj.translation.z}},
                     {"rotation", {rj.rotation.x, rj.rotation.y, rj.rotation.z, rj.rotation.w}}};
        json kids = json::array();
        for (size_t c = 0; c < raw.joints.size(); ++c)
            if (raw.joints[c].parent == static_cast<int>(k)) kids.push_back(c);
        if (!kids.empty()) node["children"] = kids;
        nodes.push_back(node);
    }
    json joints = json::array();
    for (size_t k = 0; k < raw.joints.size(); ++k) joints.push_back(k);
    json skin = {{"joints", joints}};
    const glm::quat rest = raw.joints[static_cast<size_t>(animated)].rotation;
    const glm::quat turned = glm::normalize(rest * glm::angleAxis(angle, glm::vec3(1, 0, 0)));
    const float times[2] = {0.0f, 1.0f};
    const float rotations[8] = {rest.x, rest.y, rest.z, rest.w, turned.x, turned.y, turned.z, turned.w};
    const int t_acc = add(times, sizeof times, 5126, "SCALAR", 2, {{"min", {0.0}}, {"max", {1.0}}});
    const int r_acc = add(rotations, sizeof rotations, 5126, "VEC4", 2);
    json scene_nodes = {0};
    if (mesh) {
        const size_t n = raw.joints.size();
        std::vector<glm::mat4> model(n);
        for (size_t k = 0; k < n; ++k) {
            const glm::mat4 local = glm::translate(glm::mat4(1.0f), raw.joints[k].translation) * glm::mat4_cast(raw.joints[k].rotation);
            model[k] = raw.joints[k].parent < 0 ? local : model[static_cast<size_t>(raw.joints[k].parent)] * local;
        }
        std::vector<glm::vec3> positions;
        std::vector<uint16_t> vertex_joints, indices;
        std::vector<float> weights;
        std::vector<glm::mat4> inverse_bind;
        for (size_t k = 0; k < n; ++k) {
            const glm::vec3 c(model[k][3]);
            const float r = 0.03f * glm::length(glm::vec3(model[k][0]));  // 3 cm in the file's units
            for (const glm::vec3& o : {glm::vec3(r, 0, 0), glm::vec3(0, r, 0), glm::vec3(0, 0, r)}) {
                indices.push_back(static_cast<uint16_t>(positions.size()));
                positions.push_back(c + o);
                vertex_joints.insert(vertex_joints.end(), {static_cast<uint16_t>(k), 0, 0, 0});
                weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
            }
            inverse_bind.push_back(glm::inverse(model[k]));
        }
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        const int p_acc = add(positions.data(), positions.size() * sizeof(glm::vec3), 5126, "VEC3", positions.size(),
                              {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}});
        const int j_acc = add(vertex_joints.data(), vertex_joints.size() * 2, 5123, "VEC4", positions.size());
        const int w_acc = add(weights.data(), weights.size() * 4, 5126, "VEC4", positions.size());
        const int i_acc = add(indices.data(), indices.size() * 2, 5123, "SCALAR", indices.size());
        const int b_acc = add(inverse_bind.data(), n * sizeof(glm::mat4), 5126, "MAT4", n);
        skin["inverseBindMatrices"] = b_acc;
        j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", p_acc}, {"JOINTS_0", j_acc}, {"WEIGHTS_0", w_acc}}},
                                                               {"indices", i_acc}}})}}});
        nodes.push_back({{"name", "body"}, {"mesh", 0}, {"skin", 0}});
        scene_nodes.push_back(nodes.size() - 1);
    }
    j["nodes"] = nodes;
    j["scenes"] = json::array({{{"nodes", scene_nodes}}});
    j["skins"] = json::array({skin});
    static const char* k64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string b64;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const auto at = [&](size_t q) { return q < bytes.size() ? static_cast<uint32_t>(static_cast<unsigned char>(bytes[q])) : 0u; };
        const uint32_t v = (at(i) << 16) | (at(i + 1) << 8) | at(i + 2);
        b64 += k64[(v >> 18) & 63];
        b64 += k64[(v >> 12) & 63];
        b64 += i + 1 < bytes.size() ? k64[(v >> 6) & 63] : '=';
        b64 += i + 2 < bytes.size() ? k64[v & 63] : '=';
    }
    j["buffers"] = json::array({{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + b64}}});
    j["bufferViews"] = views;
    j["accessors"] = accessors;
    j["animations"] = json::array({{{"name", "sway"},
                                    {"samplers", json::array({{{"input", t_acc}, {"output", r_acc}, {"interpolation", "LINEAR"}}})},
                                    {"channels", json::array({{{"sampler", 0}, {"target", {{"node", animated}, {"path", "rotation"}}}}})}}});
    return j.dump(1);
}

/// Writes `text` to `path` (a test failure when it cannot).
inline void write_text(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    EXPECT_TRUE(static_cast<bool>(f)) << path;
    f << text;
}

/// Canonical -> file name tables of the conventions, for the canonical joints each one has.
inline std::map<std::string, std::string> sided(const std::map<std::string, std::string>& centre,
                                                const std::map<std::string, std::string>& left_right_pattern,
                                                const std::string& left, const std::string& right) {
    // left_right_pattern: canonical left name -> file name with "%" for the side marker.
    std::map<std::string, std::string> out = centre;
    for (const auto& [canonical, pattern] : left_right_pattern) {
        std::string l = pattern, r = pattern;
        const size_t at = pattern.find('%');
        l.replace(at, 1, left);
        r.replace(at, 1, right);
        out[canonical] = l;
        std::string rc = canonical;
        if (rc.rfind("Left", 0) == 0) rc = "Right" + rc.substr(4);
        else if (rc == "lhand") rc = "rhand";
        else if (rc[0] == 'L') rc[0] = 'R';
        out[rc] = r;
    }
    return out;
}

/// Poser (classic) names: hip, abdomen, chest, neck, head, lThigh, lShin, lFoot, lToe, lCollar,
/// lShldr, lForeArm, lHand and the right side.
inline std::map<std::string, std::string> poser_names() {
    return sided({{"Hips", "hip"}, {"lowerback", "abdomen"}, {"Chest2", "chest"}, {"lowerneck", "neck"}, {"Head", "head"}},
                 {{"LeftHip", "%Thigh"}, {"LeftKnee", "%Shin"}, {"LeftAnkle", "%Foot"}, {"LeftToe", "%Toe"},
                  {"LeftCollar", "%Collar"}, {"LeftShoulder", "%Shldr"}, {"LeftElbow", "%ForeArm"}, {"LeftWrist", "%Hand"}},
                 "l", "r");
}

/// DAZ Genesis names: hip, abdomenLower/Upper, chestUpper, neckLower/Upper, head, lThighBend, lShin,
/// lFoot, lToe, lCollar, lShldrBend, lForearmBend, lHand and the right side.
inline std::map<std::string, std::string> daz_names() {
    return sided({{"Hips", "hip"}, {"lowerback", "abdomenLower"}, {"Chest", "abdomenUpper"}, {"Chest2", "chestUpper"},
                  {"lowerneck", "neckLower"}, {"Neck", "neckUpper"}, {"Head", "head"}},
                 {{"LeftHip", "%ThighBend"}, {"LeftKnee", "%Shin"}, {"LeftAnkle", "%Foot"}, {"LeftToe", "%Toe"},
                  {"LeftCollar", "%Collar"}, {"LeftShoulder", "%ShldrBend"}, {"LeftElbow", "%ForearmBend"},
                  {"LeftWrist", "%Hand"}},
                 "l", "r");
}

/// Blender Rigify names (spine ... spine.006, thigh.L, shin.L, ...), each with `prefix` ("DEF-" or "").
inline std::map<std::string, std::string> rigify_names(const std::string& prefix) {
    const std::string p = prefix;
    return sided({{"Hips", p + "spine"}, {"lowerback", p + "spine.001"}, {"Chest", p + "spine.002"}, {"Chest2", p + "spine.003"},
                  {"lowerneck", p + "spine.004"}, {"Neck", p + "spine.005"}, {"Head", p + "spine.006"}},
                 {{"LeftHip", p + "thigh.%"}, {"LeftKnee", p + "shin.%"}, {"LeftAnkle", p + "foot.%"}, {"LeftToe", p + "toe.%"},
                  {"LeftCollar", p + "shoulder.%"}, {"LeftShoulder", p + "upper_arm.%"}, {"LeftElbow", p + "forearm.%"},
                  {"LeftWrist", p + "hand.%"}},
                 "L", "R");
}

/// Unity Humanoid bone names without UpperChest, the side written by `pattern` around "%" (e.g.
/// "Left%" gives LeftUpperLeg, "%.L" gives UpperLeg.L with `left`/`right` filling the "%").
inline std::map<std::string, std::string> unity_names(const std::string& left, const std::string& right, bool prefix) {
    auto at = [&](const char* base) { return prefix ? std::string("%") + base : std::string(base) + "%"; };
    return sided({{"Hips", "Hips"}, {"lowerback", "Spine"}, {"Chest", "Chest"}, {"lowerneck", "Neck"}, {"Head", "Head"}},
                 {{"LeftHip", at("UpperLeg")}, {"LeftKnee", at("LowerLeg")}, {"LeftAnkle", at("Foot")}, {"LeftToe", at("Toes")},
                  {"LeftCollar", at("Shoulder")}, {"LeftShoulder", at("UpperArm")}, {"LeftElbow", at("LowerArm")},
                  {"LeftWrist", at("Hand")}},
                 left, right);
}

/// Mixamo / HumanIK names with the "mixamorig:" namespace (Hips, Spine, Spine1, Spine2, Neck,
/// Head, LeftUpLeg, LeftLeg, LeftFoot, LeftToeBase, LeftShoulder = collar, LeftArm, LeftForeArm,
/// LeftHand, LeftHandMiddle1, LeftHandThumb1 and the right side).
inline std::map<std::string, std::string> mixamo_names() {
    return sided({{"Hips", "mixamorig:Hips"}, {"lowerback", "mixamorig:Spine"}, {"Chest", "mixamorig:Spine1"},
                  {"Chest2", "mixamorig:Spine2"}, {"lowerneck", "mixamorig:Neck"}, {"Head", "mixamorig:Head"}},
                 {{"LeftHip", "mixamorig:%UpLeg"}, {"LeftKnee", "mixamorig:%Leg"}, {"LeftAnkle", "mixamorig:%Foot"},
                  {"LeftToe", "mixamorig:%ToeBase"}, {"LeftCollar", "mixamorig:%Shoulder"}, {"LeftShoulder", "mixamorig:%Arm"},
                  {"LeftElbow", "mixamorig:%ForeArm"}, {"LeftWrist", "mixamorig:%Hand"},
                  {"LFingers", "mixamorig:%HandMiddle1"}, {"LThumb", "mixamorig:%HandThumb1"}},
                 "Left", "Right");
}

/// Unity Humanoid bone names with UpperChest (LeftUpperLeg, LeftLowerLeg, LeftFoot, LeftToes,
/// LeftShoulder, LeftUpperArm, LeftLowerArm, LeftHand and the right side).
inline std::map<std::string, std::string> unity_humanoid_names() {
    return sided({{"Hips", "Hips"}, {"lowerback", "Spine"}, {"Chest", "Chest"}, {"Chest2", "UpperChest"},
                  {"lowerneck", "Neck"}, {"Head", "Head"}},
                 {{"LeftHip", "%UpperLeg"}, {"LeftKnee", "%LowerLeg"}, {"LeftAnkle", "%Foot"}, {"LeftToe", "%Toes"},
                  {"LeftCollar", "%Shoulder"}, {"LeftShoulder", "%UpperArm"}, {"LeftElbow", "%LowerArm"},
                  {"LeftWrist", "%Hand"}},
                 "Left", "Right");
}

/// VRM humanoid bone names, camelCase (hips, spine, chest, upperChest, neck, head, leftUpperLeg,
/// ..., leftThumbProximal and the right side).
inline std::map<std::string, std::string> vrm_names() {
    return sided({{"Hips", "hips"}, {"lowerback", "spine"}, {"Chest", "chest"}, {"Chest2", "upperChest"},
                  {"lowerneck", "neck"}, {"Head", "head"}},
                 {{"LeftHip", "%UpperLeg"}, {"LeftKnee", "%LowerLeg"}, {"LeftAnkle", "%Foot"}, {"LeftToe", "%Toes"},
                  {"LeftCollar", "%Shoulder"}, {"LeftShoulder", "%UpperArm"}, {"LeftElbow", "%LowerArm"},
                  {"LeftWrist", "%Hand"}, {"LThumb", "%ThumbProximal"}},
                 "left", "right");
}

/// VRoid export node names (J_Bip_C_Hips, J_Bip_L_UpperLeg, ...).
inline std::map<std::string, std::string> vroid_names() {
    return sided({{"Hips", "J_Bip_C_Hips"}, {"lowerback", "J_Bip_C_Spine"}, {"Chest", "J_Bip_C_Chest"},
                  {"Chest2", "J_Bip_C_UpperChest"}, {"lowerneck", "J_Bip_C_Neck"}, {"Head", "J_Bip_C_Head"}},
                 {{"LeftHip", "J_Bip_%_UpperLeg"}, {"LeftKnee", "J_Bip_%_LowerLeg"}, {"LeftAnkle", "J_Bip_%_Foot"},
                  {"LeftToe", "J_Bip_%_ToeBase"}, {"LeftCollar", "J_Bip_%_Shoulder"}, {"LeftShoulder", "J_Bip_%_UpperArm"},
                  {"LeftElbow", "J_Bip_%_LowerArm"}, {"LeftWrist", "J_Bip_%_Hand"}},
                 "L", "R");
}

/// Unreal mannequin names (pelvis, spine_01..03, neck_01, head, thigh_l, calf_l, foot_l, ball_l,
/// clavicle_l, upperarm_l, lowerarm_l, hand_l, middle_01_l, thumb_01_l and the right side).
inline std::map<std::string, std::string> unreal_names() {
    return sided({{"Hips", "pelvis"}, {"lowerback", "spine_01"}, {"Chest", "spine_02"}, {"Chest2", "spine_03"},
                  {"lowerneck", "neck_01"}, {"Head", "head"}},
                 {{"LeftHip", "thigh_%"}, {"LeftKnee", "calf_%"}, {"LeftAnkle", "foot_%"}, {"LeftToe", "ball_%"},
                  {"LeftCollar", "clavicle_%"}, {"LeftShoulder", "upperarm_%"}, {"LeftElbow", "lowerarm_%"},
                  {"LeftWrist", "hand_%"}, {"LFingers", "middle_01_%"}, {"LThumb", "thumb_01_%"}},
                 "l", "r");
}

/// A four-legged skeleton in centimetres (pelvis, spine, skull, back and front thighs and paws, tail):
/// no humanoid convention matches it.
inline RawSkeleton quadruped() {
    RawSkeleton raw;
    auto add = [&](const char* name, int parent, glm::vec3 t) {
        raw.joints.push_back(RawJoint{name, parent, t});
        return static_cast<int>(raw.joints.size()) - 1;
    };
    const int pelvis = add("pelvis", -1, {0, 60, -40});  // centimetres
    const int chest = add("spine", pelvis, {0, 5, 80});
    add("skull", chest, {0, 20, 25});
    for (const char* s : {"l", "r"}) {
        const float x = s[0] == 'l' ? 12.0f : -12.0f;
        const int back = add((std::string("back_thigh_") + s).c_str(), pelvis, {x, -5, 0});
        add((std::string("back_paw_") + s).c_str(), back, {0, -50, 0});
        const int front = add((std::string("front_thigh_") + s).c_str(), chest, {x, -5, 0});
        add((std::string("front_paw_") + s).c_str(), front, {0, -55, 0});
    }
    add("tail", pelvis, {0, 5, -30});
    return raw;
}

/// Names no convention knows (CesiumMan-like: torso_1, leg_L_1, arm_R_2 ...).
inline std::map<std::string, std::string> odd_names() {
    return sided({{"Hips", "torso_1"}, {"Chest2", "torso_3"}, {"lowerneck", "neck_1"}, {"Head", "neck_2"}},
                 {{"LeftHip", "leg_%_1"}, {"LeftKnee", "leg_%_2"}, {"LeftAnkle", "leg_%_3"}, {"LeftToe", "leg_%_5"},
                  {"LeftShoulder", "arm_%_4"}, {"LeftElbow", "arm_%_3"}, {"LeftWrist", "arm_%_2"}},
                 "L", "R");
}

/// The canonical joints of `vrm_names()` named "Bone.000", "Bone.001", ... (names no convention
/// reads), for fixtures that map only through a VRM humanoid declaration.
inline std::map<std::string, std::string> numbered_names() {
    std::map<std::string, std::string> out;
    char buf[16];
    int k = 0;
    for (const auto& [canonical, bone] : vrm_names()) {
        std::snprintf(buf, sizeof buf, "Bone.%03d", k++);
        out[canonical] = buf;
    }
    return out;
}

/// Adds a VRM humanoid declaration to glTF `j` (written by gltf_text(raw, ...), node k = joint k):
/// every canonical joint of `names` (canonical -> joint name in `raw`) declared as its VRM bone
/// (vrm_names()), in VRM 1.0's form (VRMC_vrm, bone -> {node}) or VRM 0.x's (VRM, [{bone, node}]).
/// VRM 1.0's thumb is "thumbMetacarpal".
inline void add_vrm_humanoid(nlohmann::json& j, const RawSkeleton& raw, const std::map<std::string, std::string>& names, bool vrm1) {
    nlohmann::json bones = vrm1 ? nlohmann::json::object() : nlohmann::json::array();
    const auto vrm = vrm_names();
    for (const auto& [canonical, joint] : names) {
        int node = -1;
        for (size_t k = 0; k < raw.joints.size(); ++k)
            if (raw.joints[k].name == joint) node = static_cast<int>(k);
        std::string bone = vrm.at(canonical);
        if (vrm1 && bone.find("ThumbProximal") != std::string::npos) bone.replace(bone.find("Proximal"), 8, "Metacarpal");
        if (vrm1) bones[bone] = {{"node", node}};
        else bones.push_back({{"bone", bone}, {"node", node}});
    }
    const char* name = vrm1 ? "VRMC_vrm" : "VRM";
    j["extensionsUsed"] = {name};
    j["extensions"][name]["humanoid"]["humanBones"] = bones;
}

}  // namespace aloha::test
