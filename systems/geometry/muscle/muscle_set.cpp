#include "systems/geometry/muscle/muscle_set.hpp"

#include "engine/anim/rest_pose.hpp"
#include "systems/geometry/muscle/superellipsoid.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace aloha {

namespace {

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Unit vector along the part of `v` orthogonal to `axis`, or zero when they are (nearly) parallel.
glm::vec3 perpendicular_part(glm::vec3 v, glm::vec3 axis) {
    const glm::vec3 p = v - glm::dot(v, axis) * axis;
    const float n = glm::length(p);
    return n > 1e-6f ? p / n : glm::vec3(0.0f);
}

}  // namespace

int MuscleSet::find(const std::string& name) const {
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return static_cast<int>(i);
    return -1;
}

void MuscleSet::push_back(const std::string& name, int origin, glm::vec3 origin_off, int insertion,
                          glm::vec3 insertion_off, glm::vec3 depth, float vol, float p, glm::vec2 ab, float fat,
                          float length) {
    names.push_back(name);
    origin_joint.push_back(static_cast<int16_t>(origin));
    insertion_joint.push_back(static_cast<int16_t>(insertion));
    origin_offset.push_back(origin_off);
    insertion_offset.push_back(insertion_off);
    depth_hint.push_back(depth);
    volume.push_back(vol);
    ratio.push_back(p);
    exponents.push_back(ab);
    volume_factor.push_back(static_cast<float>(superellipsoid_volume_factor(ab.x, ab.y)));
    fat_thickness.push_back(fat);
    rest_length.push_back(length);
    fat_region.push_back(0);
    trunk_skin.push_back(0);
}

std::vector<glm::mat4> rest_model_matrices(const Skeleton& skeleton) { return skeleton_rest_model(skeleton); }

glm::vec3 bone_vector(const Skeleton& skeleton, int joint) {
    const auto parents = skeleton.parents();
    for (int c = joint + 1; c < skeleton.joint_count(); ++c) {
        if (parents[static_cast<size_t>(c)] != joint) continue;
        const glm::vec3 t = skeleton.rest_translations()[static_cast<size_t>(c)];
        if (glm::length(t) > 1e-6f) return t;
    }
    return glm::vec3(0.0f);
}

Result<MuscleSet> resolve_muscles(std::span<const MuscleDef> defs, const Skeleton& skeleton,
                                  const std::string& source_name, std::span<const glm::mat4> rest_model) {
    std::vector<glm::mat4> own_rest;
    if (rest_model.empty()) {
        own_rest = rest_model_matrices(skeleton);
        rest_model = own_rest;
    }
    std::vector<Error> errors;
    if (rest_model.size() != static_cast<size_t>(skeleton.joint_count()))
        return make_error(source_name, "rest pose has " + std::to_string(rest_model.size()) +
                                           " matrices but the skeleton has " +
                                           std::to_string(skeleton.joint_count()) + " joints");
    MuscleSet set;
    set.joint_count = skeleton.joint_count();
    for (size_t i = 0; i < defs.size(); ++i) {
        const MuscleDef& d = defs[i];
        const std::string base = d.source_path.empty() ? "/muscles/" + std::to_string(i) : d.source_path;
        const size_t before = errors.size();
        auto fail = [&](const std::string& where, const std::string& what) {
            errors.push_back(make_error(source_name, "muscle '" + d.name + "': " + what, 0, 0, base + where));
        };
        if (d.name.empty()) fail("/name", "name is empty");
        else if (set.find(d.name) >= 0) fail("/name", "duplicate muscle name");
        // Anchors: joint lookup, along/offset -> offset in the joint frame, rest model-space point.
        auto anchor = [&](const MuscleAnchor& a, const char* key, int& joint, glm::vec3& offset, glm::vec3& rest_point) {
            const std::string where = std::string("/") + key;
            joint = skeleton.find(a.joint);
            if (joint < 0) return fail(where + "/joint", "unknown joint '" + a.joint + "'");
            if (!std::isfinite(a.along) || !finite3(a.offset)) return fail(where, "anchor has a NaN or infinite value");
            offset = a.offset;
            if (a.along != 0.0f) {
                const glm::vec3 bone = bone_vector(skeleton, joint);
                if (glm::length(bone) <= 1e-6f)
                    return fail(where + "/along", "joint '" + a.joint + "' has a zero-length bone, so 'along' cannot be used");
                offset += a.along * bone;
            }
            rest_point = glm::vec3(rest_model[static_cast<size_t>(joint)] * glm::vec4(offset, 1.0f));
        };
        int oj = -1, ij = -1;
        glm::vec3 ooff{0.0f}, ioff{0.0f}, opos{0.0f}, ipos{0.0f};
        anchor(d.origin, "origin", oj, ooff, opos);
        anchor(d.insertion, "insertion", ij, ioff, ipos);
        if (!valid_super_exponents(d.exponent_a, d.exponent_b))
            fail("/exponents", "exponents (" + std::to_string(d.exponent_a) + ", " + std::to_string(d.exponent_b) +
                                   ") must lie in [" + std::to_string(kMinSuperExponent) + ", " +
                                   std::to_string(kMaxSuperExponent) + "]");
        if (!(d.fat_thickness >= 0.0f) || !std::isfinite(d.fat_thickness))
            fail("/fat_thickness", "fat thickness must be >= 0 metres");
        const bool use_radii = d.rest_radii != glm::vec2(0.0f);
        if (use_radii) {
            if (!(d.rest_radii.x > 0.0f && d.rest_radii.y > 0.0f) || !std::isfinite(d.rest_radii.x + d.rest_radii.y))
                fail("/radii", "rest radii must both be positive metres");
        } else {
            if (!(d.volume > 0.0f) || !std::isfinite(d.volume)) fail("/volume", "volume must be positive (m^3)");
            if (!(d.ratio > 0.0f) || !std::isfinite(d.ratio)) fail("/ratio", "ratio p = ry/rz must be positive");
        }
        if (!finite3(d.depth_axis)) fail("/depth_axis", "depth axis has a NaN or infinite value");
        if (errors.size() != before) continue;

        const float length = glm::length(ipos - opos);
        if (!(length > 1e-4f)) {
            fail("", "origin and insertion coincide at the rest pose (length " + std::to_string(length) + " m)");
            continue;
        }
        const glm::vec3 axis_model = (ipos - opos) / length;
        // Depth hint in the origin frame: the given axis, else the direction from the bone to the muscle.
        const glm::mat3 orot = glm::mat3(rest_model[static_cast<size_t>(oj)]);
        const glm::mat3 to_origin = glm::inverse(orot);
        const glm::vec3 axis_local = glm::normalize(to_origin * axis_model);
        glm::vec3 hint = perpendicular_part(d.depth_axis, axis_local);
        if (hint == glm::vec3(0.0f) && d.depth_axis != glm::vec3(0.0f)) {
            fail("/depth_axis", "depth axis is parallel to the muscle (origin to insertion)");
            continue;
        }
        if (hint == glm::vec3(0.0f)) {
            const glm::vec3 mid_local = to_origin * (0.5f * (opos + ipos) - glm::vec3(rest_model[static_cast<size_t>(oj)][3]));
            hint = perpendicular_part(mid_local, axis_local);
        }
        for (int k = 0; k < 3 && hint == glm::vec3(0.0f); ++k) {  // muscle on the bone axis: any stable axis
            glm::vec3 e(0.0f);
            e[(k + 2) % 3] = 1.0f;
            hint = perpendicular_part(e, axis_local);
        }
        const glm::vec2 ab(d.exponent_a, d.exponent_b);
        float vol = d.volume, p = d.ratio;
        if (use_radii) {
            p = d.rest_radii.x / d.rest_radii.y;
            vol = static_cast<float>(superellipsoid_volume(glm::dvec3(0.5 * length, d.rest_radii.x, d.rest_radii.y), ab.x, ab.y));
        }
        set.push_back(d.name, oj, ooff, ij, ioff, hint, vol, p, ab, d.fat_thickness, length);
        set.trunk_skin.back() = d.trunk_skin ? 1 : 0;
        if (d.fat_region) {  // one entry per region name, in order of first use
            size_t k = 0;
            while (k < set.fat_regions.size() && set.fat_regions[k].name != d.fat_region->name) ++k;
            if (k == set.fat_regions.size() && k < kMaxFatRegions) set.fat_regions.push_back(*d.fat_region);
            if (k < kMaxFatRegions) set.fat_region.back() = static_cast<uint8_t>(k + 1);
            else fail("/fat_region", "more than " + std::to_string(kMaxFatRegions) + " fat regions are used");
        }
    }
    if (!errors.empty()) {
        Error first = errors.front();
        if (errors.size() > 1)
            first.message += "\n" + join_errors(std::vector<Error>(errors.begin() + 1, errors.end()));
        return first;
    }
    return set;
}

}  // namespace aloha
