// glTF animations -> RawAnimation (raw joint order): sampler checks, STEP / CUBICSPLINE handling,
// folding of non-joint ancestor transforms into the keys, shift of the first key to t = 0.
#include "engine/assets/gltf_detail.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
    std::vector<uint8_t> seen(joints.size() * 3, 0);
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
        const int j = joint_of_node[static_cast<size_t>(ch.target_node)];
        if (j < 0) {
            notes->push_back(cw + ": target nodes[" + std::to_string(ch.target_node) + "] is not a joint; channel skipped");
            continue;
        }
        uint8_t& dup = seen[static_cast<size_t>(j) * 3 + static_cast<size_t>(path)];
        if (dup) return make_error(file, "second '" + ch.target_path + "' channel for nodes[" + std::to_string(ch.target_node) + "]", 0, 0, cw);
        dup = 1;
        Result<Keys> keys = read_sampler(model, anim, ch.sampler, path, file, cw);
        if (!keys.ok()) return keys.error();
        const JointBinding& b = joints[static_cast<size_t>(j)];
        Trs fold;
        if (b.folded) {
            Result<Trs> f = decompose(b.fold, file, "nodes[" + std::to_string(b.node) + "] ancestors");
            if (!f.ok()) return f.error();
            fold = f.value();
        }
        RawJointTracks& t = clip.tracks[static_cast<size_t>(j)];
        for (size_t k = 0; k < keys.value().times.size(); ++k) {
            const glm::vec4 v = keys.value().values[k];
            const float time = keys.value().times[k];
            if (path == Path::kTranslation) {
                t.translations.times.push_back(time);
                t.translations.values.push_back(b.folded ? glm::vec3(b.fold * glm::vec4(glm::vec3(v), 1.0f)) : glm::vec3(v));
            } else if (path == Path::kRotation) {
                const glm::quat q(v.w, v.x, v.y, v.z);
                t.rotations.times.push_back(time);
                t.rotations.values.push_back(b.folded ? glm::normalize(fold.r * q) : q);
            } else {
                t.scales.times.push_back(time);
                t.scales.values.push_back(b.folded ? fold.s * glm::vec3(v) : glm::vec3(v));
            }
        }
        first = std::min(first, keys.value().times.front());
        last = std::max(last, keys.value().times.back());
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
