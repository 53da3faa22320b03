// glTF animations -> RawAnimation (raw joint order): sampler checks, STEP / CUBICSPLINE handling,
// folding of non-joint ancestor transforms (static or animated) into the keys, shift of the first key to t = 0.
#include "engine/assets/gltf_detail.hpp"

#include "engine/anim/pose.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace aloha::gltf_detail {

namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

enum class Path { kTranslation, kRotation, kScale };

// Keys of one channel before time shifting: times and values as vec4 (xyz or quaternion xyzw).
struct Keys {
    std::vector<float> times;
    std::vector<glm::vec4> values;
};

Result<Keys> read_sampler(const tinygltf::Model& model, const tinygltf::Animation& anim, int sampler_index, Path path,
                          const std::string& file, const std::string& where) {
    if (sampler_index < 0 || static_cast<size_t>(sampler_index) >= anim.samplers.size())
        return make_error(file, "sampler " + std::to_string(sampler_index) + " is out of range (the animation has " +
                                    std::to_string(anim.samplers.size()) + " samplers)", 0, 0, where);
    const std::string sw = where.substr(0, where.find(".channels")) + ".samplers[" + std::to_string(sampler_index) + "]";
    const tinygltf::AnimationSampler& s = anim.samplers[static_cast<size_t>(sampler_index)];
    const std::string interp = s.interpolation.empty() ? "LINEAR" : s.interpolation;
    if (interp != "LINEAR" && interp != "STEP" && interp != "CUBICSPLINE")
        return make_error(file, "unknown interpolation '" + interp + "'", 0, 0, sw);
    Result<std::vector<float>> times = read_floats(model, s.input, TINYGLTF_TYPE_SCALAR, {kFloat}, file, sw + ".input");
    if (!times.ok()) return times.error();
    Keys keys;
    keys.times = std::move(times).value();
    for (size_t k = 0; k < keys.times.size(); ++k) {
        if (!std::isfinite(keys.times[k])) return make_error(file, "key time " + std::to_string(k) + " is NaN or infinite", 0, 0, sw + ".input");
        if (k > 0 && !(keys.times[k] > keys.times[k - 1]))
            return make_error(file, "key times are not strictly increasing at key " + std::to_string(k), 0, 0, sw + ".input");
    }
    const bool rotation = path == Path::kRotation;
    const std::vector<int> allowed = rotation ? std::vector<int>{kFloat, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                                 TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}
                                              : std::vector<int>{kFloat};
    const size_t comps = rotation ? 4 : 3;
    Result<std::vector<float>> out = read_floats(model, s.output, rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, allowed, file, sw + ".output");
    if (!out.ok()) return out.error();
    const size_t per_key = interp == "CUBICSPLINE" ? 3 : 1;
    const size_t n = keys.times.size();
    if (out.value().size() != n * per_key * comps)
        return make_error(file, "output has " + std::to_string(out.value().size() / comps) + " values for " + std::to_string(n) +
                                    " key times (" + interp + " needs " + std::to_string(n * per_key) + ")", 0, 0, sw + ".output");
    keys.values.resize(n);
    for (size_t k = 0; k < n; ++k) {
        const size_t base = (k * per_key + (per_key == 3 ? 1 : 0)) * comps;  // CUBICSPLINE: the value of each triple
        glm::vec4 v(0.0f);
        for (size_t c = 0; c < comps; ++c) v[static_cast<int>(c)] = out.value()[base + c];
        if (!std::isfinite(v.x + v.y + v.z + v.w)) return make_error(file, "value " + std::to_string(k) + " is NaN or infinite", 0, 0, sw + ".output");
        if (rotation) {
            const float len = glm::length(v);
            if (len < 1e-6f) return make_error(file, "rotation " + std::to_string(k) + " has zero length", 0, 0, sw + ".output");
            v /= len;
        }
        keys.values[k] = v;
    }
    if (interp == "STEP" && n > 1) {  // hold each value until just before the next key
        Keys held;
        for (size_t k = 0; k < n; ++k) {
            held.times.push_back(keys.times[k]);
            held.values.push_back(keys.values[k]);
            if (k + 1 == n) break;
            const float gap = keys.times[k + 1] - keys.times[k];
            const float hold = keys.times[k + 1] - std::min(1e-4f, 0.25f * gap);
            if (hold > keys.times[k] && hold < keys.times[k + 1]) {
                held.times.push_back(hold);
                held.values.push_back(keys.values[k]);
            }
        }
        return held;
    }
    return keys;
}

// Value of `keys` at time t: linear between keys (slerp on the shorter arc for rotations, as glTF's LINEAR
// interpolation of rotations prescribes), held before the first key and after the last.
glm::vec4 sample(const Keys& keys, float t, bool rotation) {
    const std::vector<float>& ts = keys.times;
    if (t <= ts.front()) return keys.values.front();
    if (t >= ts.back()) return keys.values.back();
    const size_t hi = static_cast<size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin());
    const float a = (t - ts[hi - 1]) / (ts[hi] - ts[hi - 1]);
    if (!rotation) return glm::mix(keys.values[hi - 1], keys.values[hi], a);
    const glm::quat q0(keys.values[hi - 1].w, keys.values[hi - 1].x, keys.values[hi - 1].y, keys.values[hi - 1].z);
    glm::quat q1(keys.values[hi].w, keys.values[hi].x, keys.values[hi].y, keys.values[hi].z);
    const glm::quat q = glm::slerp(q0, glm::dot(q0, q1) < 0.0f ? -q1 : q1, a);
    return {q.x, q.y, q.z, q.w};
}

// A node's channels in one clip: translation, rotation, scale (each optional).
using NodeKeys = std::array<std::optional<Keys>, 3>;

// Local matrix of `node` at time t: its animated channels sampled, the rest from its rest TRS `rest`.
glm::mat4 local_at(const NodeKeys* keys, const Trs& rest, float t) {
    glm::vec3 tr = rest.t, sc = rest.s;
    glm::quat q = rest.r;
    if (keys && (*keys)[0]) tr = glm::vec3(sample(*(*keys)[0], t, false));
    if (keys && (*keys)[1]) {
        const glm::vec4 v = sample(*(*keys)[1], t, true);
        q = glm::normalize(glm::quat(v.w, v.x, v.y, v.z));
    }
    if (keys && (*keys)[2]) sc = glm::vec3(sample(*(*keys)[2], t, false));
    return trs_matrix(tr, q, sc);
}

Result<Trs> rest_trs(const tinygltf::Model& model, int node, const std::string& file) {
    Result<glm::mat4> m = node_local_matrix(model, node, file);
    if (!m.ok()) return m.error();
    return decompose(m.value(), file, "nodes[" + std::to_string(node) + "]");
}

// Tracks of joint `b` whose folded ancestors (b.chain) are animated: at every key time of the joint and of
// those ancestors, the product of the ancestors' local matrices and the joint's, split into TRS keys.
Status fold_animated_ancestors(const tinygltf::Model& model, const JointBinding& b, const NodeKeys* own,
                               const std::map<int, NodeKeys>& node_keys, const std::string& file, const std::string& where,
                               RawJointTracks* out) {
    std::vector<float> times;
    std::vector<const NodeKeys*> chain_keys;
    std::vector<Trs> chain_rest;
    auto gather = [&](const NodeKeys* keys) {
        if (!keys) return;
        for (const std::optional<Keys>& k : *keys)
            if (k) times.insert(times.end(), k->times.begin(), k->times.end());
    };
    for (const int node : b.chain) {
        const auto it = node_keys.find(node);
        chain_keys.push_back(it == node_keys.end() ? nullptr : &it->second);
        gather(chain_keys.back());
        Result<Trs> rest = rest_trs(model, node, file);
        if (!rest.ok()) return rest.error();
        chain_rest.push_back(rest.value());
    }
    gather(own);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    Result<Trs> joint_rest = rest_trs(model, b.node, file);
    if (!joint_rest.ok()) return joint_rest.error();
    for (const float t : times) {
        glm::mat4 m(1.0f);
        for (size_t c = 0; c < b.chain.size(); ++c) m = m * local_at(chain_keys[c], chain_rest[c], t);
        m = m * local_at(own, joint_rest.value(), t);
        Result<Trs> trs = decompose(m, file, where + " at key time " + std::to_string(t));
        if (!trs.ok()) return trs.error();
        out->translations.times.push_back(t);
        out->translations.values.push_back(trs.value().t);
        out->rotations.times.push_back(t);
        out->rotations.values.push_back(trs.value().r);
        out->scales.times.push_back(t);
        out->scales.values.push_back(trs.value().s);
    }
    return {};
}

}  // namespace

Result<RawAnimation> read_clip(const tinygltf::Model& model, int index, const std::vector<JointBinding>& joints,
                               const std::string& file, std::vector<std::string>* notes, size_t* morph_channels) {
    const tinygltf::Animation& anim = model.animations[static_cast<size_t>(index)];
    const std::string aw = "animations[" + std::to_string(index) + "]";
    RawAnimation clip;
    clip.name = anim.name.empty() ? "clip" + std::to_string(index) : anim.name;
    clip.tracks.resize(joints.size());
    std::vector<int> joint_of_node(model.nodes.size(), -1);
    for (size_t j = 0; j < joints.size(); ++j) joint_of_node[static_cast<size_t>(joints[j].node)] = static_cast<int>(j);
    // Nodes folded into some joint (animating one moves the joints below it).
    std::vector<uint8_t> folded(model.nodes.size(), 0);
    for (const JointBinding& b : joints)
        for (const int node : b.chain) folded[static_cast<size_t>(node)] = 1;
    std::vector<NodeKeys> joint_keys(joints.size());
    std::map<int, NodeKeys> node_keys;  // animated folded ancestors
    float first = std::numeric_limits<float>::infinity(), last = -std::numeric_limits<float>::infinity();
    for (size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = anim.channels[c];
        const std::string cw = aw + ".channels[" + std::to_string(c) + "]";
        if (ch.target_node < 0 || static_cast<size_t>(ch.target_node) >= model.nodes.size())
            return make_error(file, "target node " + std::to_string(ch.target_node) + " is out of range (the file has " +
                                        std::to_string(model.nodes.size()) + " nodes)", 0, 0, cw);
        Path path;
        if (ch.target_path == "translation") path = Path::kTranslation;
        else if (ch.target_path == "rotation") path = Path::kRotation;
        else if (ch.target_path == "scale") path = Path::kScale;
        else if (ch.target_path == "weights") {
            ++*morph_channels;
            continue;
        } else {
            return make_error(file, "unknown target path '" + ch.target_path + "'", 0, 0, cw);
        }
        const auto node = static_cast<size_t>(ch.target_node);
        const int j = joint_of_node[node];
        if (j < 0 && !folded[node]) {
            notes->push_back(cw + ": target nodes[" + std::to_string(ch.target_node) + "] is not a joint nor above one; channel skipped");
            continue;
        }
        std::optional<Keys>& slot = j >= 0 ? joint_keys[static_cast<size_t>(j)][static_cast<size_t>(path)]
                                           : node_keys[ch.target_node][static_cast<size_t>(path)];
        if (slot) return make_error(file, "second '" + ch.target_path + "' channel for nodes[" + std::to_string(ch.target_node) + "]", 0, 0, cw);
        Result<Keys> keys = read_sampler(model, anim, ch.sampler, path, file, cw);
        if (!keys.ok()) return keys.error();
        slot = std::move(keys).value();
        first = std::min(first, slot->times.front());
        last = std::max(last, slot->times.back());
    }
    size_t moved = 0;
    for (size_t j = 0; j < joints.size(); ++j) {
        const JointBinding& b = joints[j];
        const NodeKeys& own = joint_keys[j];
        bool animated_chain = false;
        for (const int node : b.chain) animated_chain |= node_keys.count(node) > 0;
        RawJointTracks& t = clip.tracks[j];
        if (animated_chain) {
            ++moved;
            if (Status s = fold_animated_ancestors(model, b, &own, node_keys, file, aw + " nodes[" + std::to_string(b.node) + "]", &t); !s.ok())
                return s.error();
            continue;
        }
        Trs fold;
        if (b.folded) {
            Result<Trs> f = decompose(b.fold, file, "nodes[" + std::to_string(b.node) + "] ancestors");
            if (!f.ok()) return f.error();
            fold = f.value();
        }
        for (size_t p = 0; p < 3; ++p) {
            if (!own[p]) continue;
            const Keys& keys = *own[p];
            for (size_t k = 0; k < keys.times.size(); ++k) {
                const glm::vec4 v = keys.values[k];
                const float time = keys.times[k];
                if (p == static_cast<size_t>(Path::kTranslation)) {
                    t.translations.times.push_back(time);
                    t.translations.values.push_back(b.folded ? glm::vec3(b.fold * glm::vec4(glm::vec3(v), 1.0f)) : glm::vec3(v));
                } else if (p == static_cast<size_t>(Path::kRotation)) {
                    const glm::quat q(v.w, v.x, v.y, v.z);
                    t.rotations.times.push_back(time);
                    t.rotations.values.push_back(b.folded ? glm::normalize(fold.r * q) : q);
                } else {
                    t.scales.times.push_back(time);
                    t.scales.values.push_back(b.folded ? fold.s * glm::vec3(v) : glm::vec3(v));
                }
            }
        }
    }
    if (!node_keys.empty()) {
        std::string list;
        for (const auto& [node, keys] : node_keys) list += (list.empty() ? "" : ", ") + std::string("nodes[") + std::to_string(node) + "]";
        notes->push_back(aw + ": the animation of " + list + " (above the joints, not joints) is folded into the keys of the " +
                         std::to_string(moved) + " joint" + (moved == 1 ? "" : "s") + " below");
    }
    if (first <= last) {
        clip.start_offset = first;
        clip.duration = last - first;
        for (RawJointTracks& t : clip.tracks) {
            for (float& x : t.translations.times) x -= first;
            for (float& x : t.rotations.times) x -= first;
            for (float& x : t.scales.times) x -= first;
        }
    }
    return clip;
}

}  // namespace aloha::gltf_detail
