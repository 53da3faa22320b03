// Test helper: a skeleton and built clips written as a glTF file (JSON with an embedded base64-free buffer file
// next to it), so tests can hand known animations to the glTF loader the way an exporter writes them: one node per
// joint, a skin over them, one animation per clip with a rotation channel per joint and a translation channel for
// the root, sampled at a fixed rate (LINEAR).
#pragma once

#include "engine/anim/skeleton.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/sampling.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace aloha::test {

/// Writes `path` (.gltf) and its buffer `path` + ".bin": the nodes of `sk` (rest translations and rotations, names
/// kept), a skin over all of them (no mesh), and per (name, clip) of `clips` an animation of that name sampled at
/// `fps` from 0 to the clip's end (the end included).
inline void write_gltf_with_clips(const std::string& path, const Skeleton& sk, const std::vector<std::pair<std::string, const AnimationClip*>>& clips,
                                  float fps = 60.0f) {
    using nlohmann::json;
    const size_t n = static_cast<size_t>(sk.joint_count());
    std::string bytes;
    json views = json::array(), accessors = json::array();
    auto add = [&](const std::vector<float>& data, const char* type, size_t count, json extra = json::object()) {
        views.push_back({{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", data.size() * sizeof(float)}});
        bytes.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(float));
        json a = {{"bufferView", views.size() - 1}, {"componentType", 5126}, {"count", count}, {"type", type}};
        a.update(extra);
        accessors.push_back(a);
        return static_cast<int>(accessors.size()) - 1;
    };
    json nodes = json::array();
    for (size_t j = 0; j < n; ++j) {
        const glm::vec3 t = sk.rest_translations()[j];
        const glm::quat r = sk.rest_rotations()[j];
        json node = {{"name", sk.names()[j]}, {"translation", {t.x, t.y, t.z}}, {"rotation", {r.x, r.y, r.z, r.w}}};
        json kids = json::array();
        for (size_t c = 0; c < n; ++c)
            if (sk.parents()[c] == static_cast<int16_t>(j)) kids.push_back(c);
        if (!kids.empty()) node["children"] = kids;
        nodes.push_back(node);
    }
    json joints = json::array();
    for (size_t j = 0; j < n; ++j) joints.push_back(j);
    json animations = json::array();
    for (const auto& [name, clip] : clips) {
        const int keys = static_cast<int>(std::floor(clip->duration() * fps)) + 1;
        std::vector<float> times;
        for (int k = 0; k < keys; ++k) times.push_back(static_cast<float>(k) / fps);
        if (times.back() < clip->duration()) times.push_back(clip->duration());
        std::vector<std::vector<float>> rotations(n);
        std::vector<float> root;
        std::vector<glm::vec3> tr(n), sc(n);
        std::vector<glm::quat> ro(n);
        for (const float t : times) {
            int key = 0;
            float alpha = 0.0f;
            find_key(*clip, std::min(t, clip->duration()), nullptr, &key, &alpha);
            sample_blocks(*clip, key, alpha, tr.data(), ro.data(), sc.data());
            for (size_t j = 0; j < n; ++j) rotations[j].insert(rotations[j].end(), {ro[j].x, ro[j].y, ro[j].z, ro[j].w});
            root.insert(root.end(), {tr[0].x, tr[0].y, tr[0].z});
        }
        const int input = add(times, "SCALAR", times.size(), {{"min", {times.front()}}, {"max", {times.back()}}});
        json samplers = json::array(), channels = json::array();
        for (size_t j = 0; j < n; ++j) {
            samplers.push_back({{"input", input}, {"output", add(rotations[j], "VEC4", times.size())}, {"interpolation", "LINEAR"}});
            channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", j}, {"path", "rotation"}}}});
        }
        samplers.push_back({{"input", input}, {"output", add(root, "VEC3", times.size())}, {"interpolation", "LINEAR"}});
        channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", 0}, {"path", "translation"}}}});
        animations.push_back({{"name", name}, {"samplers", samplers}, {"channels", channels}});
    }
    const std::string bin = path + ".bin";
    json j;
    j["asset"] = {{"version", "2.0"}, {"generator", "aloha tests/common/gltf_writer.hpp"}};
    j["scene"] = 0;
    j["scenes"] = json::array({{{"nodes", {0}}}});
    j["nodes"] = nodes;
    j["skins"] = json::array({{{"joints", joints}}});
    j["animations"] = animations;
    j["buffers"] = json::array({{{"uri", bin.substr(bin.find_last_of('/') + 1)}, {"byteLength", bytes.size()}}});
    j["bufferViews"] = views;
    j["accessors"] = accessors;
    std::ofstream(bin, std::ios::binary) << bytes;
    std::ofstream(path) << j.dump();
}

}  // namespace aloha::test
