#include "engine/assets/rig_normalise.hpp"

#include "engine/anim/rest_pose.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

namespace aloha {

namespace {

struct Unit {
    const char* name;
    float metres;
};

constexpr Unit kGltfUnits[] = {{"metres", 1.0f}, {"centimetres", 0.01f}, {"millimetres", 0.001f}};
constexpr Unit kBvhUnits[] = {{"metres", 1.0f},       {"centimetres", 0.01f},          {"millimetres", 0.001f},
                              {"inches", 0.0254f},    {"CMU units (0.056444 m)", 0.056444f}};

constexpr float kStandingPerSpan = 1.1f;  // standing height over the joints' vertical span (head joint
                                          // below the crown, lowest joint above the sole)

std::string fmt(const char* f, double a, double b = 0.0, double c = 0.0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, f, a, b, c);
    return buf;
}

// `v` snapped to the nearest signed file axis when within 30 degrees of it.
glm::vec3 snap(glm::vec3 v, bool* snapped) {
    int best = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(v[a]) > std::abs(v[best])) best = a;
    *snapped = std::abs(v[best]) > 0.8660254f;
    if (!*snapped) return v;
    glm::vec3 e(0.0f);
    e[best] = v[best] > 0.0f ? 1.0f : -1.0f;
    return e;
}

std::string axis_words(glm::vec3 v, bool snapped) {
    if (snapped)
        for (int a = 0; a < 3; ++a)
            if (std::abs(v[a]) > 0.5f) return std::string(v[a] > 0 ? "+" : "-") + "XYZ"[a];
    return fmt("(%.2f, %.2f, %.2f)", v.x, v.y, v.z);
}

glm::vec3 position(const std::vector<glm::mat4>& model, int j) { return glm::vec3(model[static_cast<size_t>(j)][3]); }

// Units of a humanoid of joint span `span` (file units): the candidate giving a standing height in
// [0.9, 2.6] m nearest 1.7 m, or nullptr.
const Unit* humanoid_unit(std::span<const Unit> units, float span) {
    const Unit* best = nullptr;
    float best_err = FLT_MAX;
    for (const Unit& u : units) {
        const float h = span * kStandingPerSpan * u.metres;
        if (h < 0.9f || h > 2.6f) continue;
        const float err = std::abs(std::log(h / 1.7f));
        if (err < best_err) best = &u, best_err = err;
    }
    return best;
}

}  // namespace

Result<RigFrame> detect_rig_frame(const Skeleton& skeleton, const HumanoidMap& map, RigFormat format, float scale,
                                  const std::string& source) {
    RigFrame frame;
    const std::vector<glm::mat4> model = skeleton_rest_model(skeleton);
    const std::span<const Unit> units = format == RigFormat::Gltf ? std::span<const Unit>(kGltfUnits) : std::span<const Unit>(kBvhUnits);
    glm::vec3 up(0, 1, 0);
    if (map.humanoid) {
        const glm::vec3 feet = 0.5f * (position(model, map.find("LeftAnkle")) + position(model, map.find("RightAnkle")));
        glm::vec3 rise = position(model, map.find("Head")) - feet;
        glm::vec3 left = position(model, map.find("LeftHip")) - position(model, map.find("RightHip"));
        if (glm::length(left) < 1e-3f * glm::length(rise))
            left = position(model, map.find("LeftShoulder")) - position(model, map.find("RightShoulder"));
        if (!(glm::length(rise) > 0.0f) || !(glm::length(left) > 0.0f))
            return make_error(source, "humanoid axes: the head and the ankles, or the left and right hips and shoulders, coincide at rest");
        bool up_snapped = false, left_snapped = false;
        up = snap(glm::normalize(rise), &up_snapped);
        glm::vec3 l = glm::normalize(left - glm::dot(left, up) * up);
        if (!std::isfinite(l.x)) return make_error(source, "humanoid axes: the left-right direction is parallel to up at rest");
        const glm::vec3 ls = snap(l, &left_snapped);
        if (left_snapped && std::abs(glm::dot(ls, up)) < 1e-3f) l = ls;
        else left_snapped = false;
        const glm::vec3 fwd = glm::cross(l, up);
        frame.axes = glm::normalize(glm::quat_cast(glm::transpose(glm::mat3(l, up, fwd))));
        frame.up = axis_words(up, up_snapped);
        frame.forward = axis_words(fwd, up_snapped && left_snapped);
        const int toes[2] = {map.find("LeftToe"), map.find("RightToe")};
        const int ankles[2] = {map.find("LeftAnkle"), map.find("RightAnkle")};
        if (toes[0] >= 0 && toes[1] >= 0 &&
            glm::dot(position(model, toes[0]) - position(model, ankles[0]), fwd) < 0.0f &&
            glm::dot(position(model, toes[1]) - position(model, ankles[1]), fwd) < 0.0f)
            frame.notes.push_back("the toes point backwards from the forward axis found from the hips: left and right may be swapped in the joint names");
    }
    float lo = FLT_MAX, hi = -FLT_MAX;
    glm::vec3 box_lo(FLT_MAX), box_hi(-FLT_MAX);
    for (size_t j = 0; j < model.size(); ++j) {
        const glm::vec3 p(model[j][3]);
        lo = std::min(lo, glm::dot(p, up));
        hi = std::max(hi, glm::dot(p, up));
        box_lo = glm::min(box_lo, p);
        box_hi = glm::max(box_hi, p);
    }
    const float span = hi - lo;
    const float size = std::max({box_hi.x - box_lo.x, box_hi.y - box_lo.y, box_hi.z - box_lo.z});
    if (scale > 0.0f) {
        frame.metres_per_unit = scale;
        frame.units = fmt("scale %g m per unit (given)", scale);
        const float h = map.humanoid ? span * kStandingPerSpan * scale : size * scale;
        if (h < 0.3f || h > 5.0f)
            frame.notes.push_back(fmt(map.humanoid ? "the given scale makes the character %.3g m tall" : "the given scale makes the character %.3g m across", h));
    } else if (map.humanoid) {
        const Unit* u = humanoid_unit(units, span);
        if (!u) {
            std::string tried;
            for (const Unit& c : units) tried += fmt("%.3g m", span * kStandingPerSpan * c.metres) + " in " + c.name + ", ";
            return make_error(source, "cannot tell the units: the humanoid would stand " + tried +
                                          "none within 0.9-2.6 m; give 'scale' (metres per file unit) on the character type");
        }
        frame.metres_per_unit = u->metres;
        frame.units = u->name;
    } else {
        const Unit* u = nullptr;
        for (const Unit& c : units)
            if (size * c.metres >= 0.2f && size * c.metres <= 5.0f) {
                u = &c;
                break;
            }
        if (format == RigFormat::Gltf && size >= 0.05f && size <= 20.0f) u = &units[0];  // glTF is metres by the spec
        if (!u)
            return make_error(source, fmt("cannot tell the units of this non-humanoid skeleton (%.4g file units across); give 'scale' (metres per file unit) on the character type", size));
        frame.metres_per_unit = u->metres;
        frame.units = u->name;
        frame.notes.push_back(std::string("not a humanoid: axes kept as in the file, units ") + u->name +
                              fmt(" (%.3g m across)", size * u->metres));
    }
    if (map.humanoid) frame.height = span * kStandingPerSpan * frame.metres_per_unit;
    return frame;
}

glm::mat4 RigNormalisation::global() const { return glm::scale(glm::mat4(1.0f), glm::vec3(metres_per_unit)) * glm::mat4_cast(axes); }

glm::mat4 RigNormalisation::correction(int joint) const {
    const auto j = static_cast<size_t>(joint);
    return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / (metres_per_unit * rest_scale[j]))) *
           glm::mat4_cast(glm::inverse(axes * rest_model[j]));
}

RigNormalisation normalise_rig(const Skeleton& skeleton, const RigFrame& frame) {
    RigNormalisation n;
    n.axes = glm::normalize(frame.axes);
    n.metres_per_unit = frame.metres_per_unit;
    const std::vector<glm::mat4> model = skeleton_rest_model(skeleton);
    const auto count = static_cast<size_t>(skeleton.joint_count());
    n.rest_model.resize(count);
    n.rest_scale.resize(count);
    bool uneven = false;
    for (size_t j = 0; j < count; ++j) {
        const glm::vec3 s(glm::length(glm::vec3(model[j][0])), glm::length(glm::vec3(model[j][1])), glm::length(glm::vec3(model[j][2])));
        n.rest_scale[j] = std::cbrt(s.x * s.y * s.z);
        uneven |= std::abs(s.x - s.y) > 1e-4f * n.rest_scale[j] || std::abs(s.y - s.z) > 1e-4f * n.rest_scale[j];
        const glm::mat3 r(glm::vec3(model[j][0]) / s.x, glm::vec3(model[j][1]) / s.y, glm::vec3(model[j][2]) / s.z);
        n.rest_model[j] = glm::normalize(glm::quat_cast(r));
    }
    if (uneven) n.notes.push_back("a joint's rest scale is not uniform: its mean is used");
    n.skeleton.joints.resize(count);
    for (size_t j = 0; j < count; ++j) {
        RawJoint& out = n.skeleton.joints[j];
        const int p = skeleton.parents()[j];
        out.name = skeleton.names()[j];
        out.parent = p;
        const glm::quat frame_p = p < 0 ? n.axes : n.axes * n.rest_model[static_cast<size_t>(p)];
        const float scale_p = p < 0 ? 1.0f : n.rest_scale[static_cast<size_t>(p)];
        out.translation = n.metres_per_unit * scale_p * (frame_p * skeleton.rest_translations()[j]);
    }
    return n;
}

void normalise_clip(RawAnimation& clip, const Skeleton& original, const RigNormalisation& n) {
    for (size_t j = 0; j < clip.tracks.size(); ++j) {
        RawJointTracks& t = clip.tracks[j];
        const int p = original.parents()[j];
        const glm::quat frame_p = p < 0 ? n.axes : n.axes * n.rest_model[static_cast<size_t>(p)];
        const glm::quat frame_j_inv = glm::inverse(n.axes * n.rest_model[j]);
        const float scale_p = p < 0 ? 1.0f : n.rest_scale[static_cast<size_t>(p)];
        for (glm::quat& q : t.rotations.values) q = glm::normalize(frame_p * q * frame_j_inv);
        for (glm::vec3& v : t.translations.values) v = n.metres_per_unit * scale_p * (frame_p * v);
        const glm::vec3 rest_s = original.rest_scales()[j];
        for (glm::vec3& s : t.scales.values) s /= rest_s;
    }
}

}  // namespace aloha
