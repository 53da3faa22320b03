#include "host/scene/scene_requests.hpp"

#include "host/scene/scene_loader.hpp"

#include <glm/gtc/quaternion.hpp>

namespace aloha {

namespace {

bool has_path(const SceneDesc& scene, const std::string& name) {
    for (const auto& p : scene.paths)
        if (p.name == name) return true;
    return false;
}

int read_type_ref(JsonObjectReader& r, const SceneDesc& scene) {
    const std::string type = r.string("type", scene.types.empty() ? "" : scene.types.front().name);
    const int index = scene_type_index(scene, type);
    if (index < 0 && !scene.types.empty()) r.error("type", "unknown character type '" + type + "'");
    return index < 0 ? 0 : index;
}

}  // namespace

RequestDesc read_request(const nlohmann::json& value, const std::string& path, const SceneDesc& scene,
                         std::vector<Error>& errors, float* weight) {
    RequestDesc out;
    JsonObjectReader r(value, path, scene.file, errors);
    if (weight) *weight = static_cast<float>(r.number("weight", 1.0, 0.0, 1.0));
    const std::string type = r.string("type", "", true);
    MotionRequest& m = out.request;
    m.duration = static_cast<float>(r.number("duration", -1.0, -1.0, 1e6));
    m.crossfade_s = static_cast<float>(r.number("crossfade", 0.2, 0.0, 10.0));
    if (type == "play") {
        m.kind = RequestKind::PlayClip;
        out.clip = r.string("clip", "", true);
        m.loop = r.boolean("loop", true) ? 1 : 0;
        m.speed = static_cast<float>(r.number("speed", 1.0, -10.0, 10.0));
        m.start_time = static_cast<float>(r.number("start", 0.0, 0.0, 1e6));
        m.root_motion = r.boolean("root_motion", true) ? 1 : 0;
    } else if (type == "walk") {
        m.kind = RequestKind::Walk;
        m.speed = static_cast<float>(r.number("speed", 1.2, 0.0, 10.0));
        out.path = r.string("path", "");
        if (!out.path.empty() && !has_path(scene, out.path)) r.error("path", "unknown path '" + out.path + "'");
        m.target = r.vec3("direction", glm::vec3(0.0f, 0.0f, 1.0f));
        if (out.path.empty() && glm::length(glm::vec3(m.target.x, 0.0f, m.target.z)) < 1e-6f)
            r.error("direction", "walk direction must not be vertical or zero");
    } else if (type == "reach" || type == "look_at") {
        m.kind = type == "reach" ? RequestKind::Reach : RequestKind::LookAt;
        out.effector = r.string("effector", type == "reach" ? "RightWrist" : "Head");
        m.target = r.vec3("target", glm::vec3(0.0f), true);
        if (const nlohmann::json* o = r.child("orientation")) {
            if (!o->is_array() || o->size() != 4) {
                r.error("orientation", "expected a quaternion [x, y, z, w]");
            } else {
                glm::quat q((*o)[3].get<float>(), (*o)[0].get<float>(), (*o)[1].get<float>(), (*o)[2].get<float>());
                if (!(glm::length(q) > 1e-6f)) r.error("orientation", "quaternion has zero length");
                else m.orientation = glm::normalize(q), m.use_orientation = 1;
            }
        }
    } else if (type == "rest") {
        m.kind = RequestKind::Rest;
    } else if (!type.empty()) {
        r.error("type", "unknown request type '" + type + "' (expected play, walk, reach, look_at or rest)");
    }
    r.reject_unknown_keys();
    return out;
}

void read_characters(JsonObjectReader& root, SceneDesc& scene, std::vector<Error>& errors) {
    const nlohmann::json* chars = root.child("characters");
    if (!chars) return;
    if (!chars->is_array()) {
        root.error("characters", "expected an array");
        return;
    }
    if (chars->size() > kMaxSceneCharacters) {
        root.error("characters", "more than " + std::to_string(kMaxSceneCharacters) + " characters");
        return;
    }
    for (size_t i = 0; i < chars->size(); ++i) {
        const std::string p = "/characters/" + std::to_string(i);
        JsonObjectReader r((*chars)[i], p, scene.file, errors);
        CharacterDesc c;
        c.type = read_type_ref(r, scene);
        c.position = r.vec3("position", glm::vec3(0.0f));
        c.heading_deg = static_cast<float>(r.number("heading_deg", 0.0, -3600.0, 3600.0));
        c.importance = static_cast<float>(r.number("importance", 0.5, 0.0, 1.0));
        c.always_full = r.boolean("always_full", false);
        if (const nlohmann::json* reqs = r.child("requests")) {
            if (!reqs->is_array() || reqs->size() > 1000) {
                r.error("requests", "expected an array of at most 1000 requests");
            } else {
                for (size_t k = 0; k < reqs->size(); ++k)
                    c.requests.push_back(read_request((*reqs)[k], p + "/requests/" + std::to_string(k), scene, errors));
            }
        }
        if (const nlohmann::json* o = r.child("overlay")) {
            // A reach or look-at layered over the requests: the same keys as those requests, plus a weight.
            RequestDesc d = read_request(*o, p + "/overlay", scene, errors, &c.overlay_weight);
            if (d.request.kind != RequestKind::Reach && d.request.kind != RequestKind::LookAt)
                r.error("overlay", "an overlay is a reach or a look_at");
            c.overlay = std::move(d);
        }
        r.reject_unknown_keys();
        scene.characters.push_back(std::move(c));
    }
}

void read_crowds(JsonObjectReader& root, SceneDesc& scene, std::vector<Error>& errors) {
    const nlohmann::json* crowds = root.child("crowds");
    if (!crowds) return;
    if (!crowds->is_array() || crowds->size() > 1000) {
        root.error("crowds", "expected an array of at most 1000 crowds");
        return;
    }
    uint64_t total = scene.characters.size();
    for (size_t i = 0; i < crowds->size(); ++i) {
        const std::string p = "/crowds/" + std::to_string(i);
        JsonObjectReader r((*crowds)[i], p, scene.file, errors);
        CrowdDesc c;
        c.type = read_type_ref(r, scene);
        // Read the count wide so 1e9 is reported as too many rather than wrapped.
        const int64_t count = r.integer("count", 0, 0, INT64_MAX, true);
        if (count > static_cast<int64_t>(kMaxSceneCharacters) || total + static_cast<uint64_t>(count) > kMaxSceneCharacters)
            r.error("count", "scene would have " + std::to_string(total + static_cast<uint64_t>(count)) +
                             " characters; at most " + std::to_string(kMaxSceneCharacters) + " are supported");
        else
            c.count = static_cast<uint32_t>(count), total += static_cast<uint64_t>(count);
        const std::string layout = r.string("layout", "grid");
        if (layout == "grid") c.layout = CrowdDesc::Layout::Grid;
        else if (layout == "disc") c.layout = CrowdDesc::Layout::Disc;
        else r.error("layout", "unknown layout '" + layout + "' (expected grid or disc)");
        c.center = r.vec3("center", glm::vec3(0.0f));
        const std::string route = r.string("walk_route", "straight");
        if (route == "straight") c.walk_route = CrowdDesc::WalkRoute::Straight;
        else if (route == "circle") c.walk_route = CrowdDesc::WalkRoute::Circle;
        else r.error("walk_route", "unknown walk route '" + route + "' (expected straight or circle)");
        c.spacing = static_cast<float>(r.number("spacing", 2.0, 0.1, 1000.0));
        c.radius = static_cast<float>(r.number("radius", 50.0, 0.1, 1e5));
        c.seed = static_cast<uint64_t>(r.integer("seed", static_cast<int64_t>(scene.seed), 0, INT64_MAX));
        c.clip = r.string("clip", "");
        if (const nlohmann::json* mix = r.child("mix")) {
            JsonObjectReader m(*mix, p + "/mix", scene.file, errors);
            c.mix.walk = static_cast<float>(m.number("walk", 0.0, 0.0, 1.0));
            c.mix.idle = static_cast<float>(m.number("idle", 0.0, 0.0, 1.0));
            c.mix.reach = static_cast<float>(m.number("reach", 0.0, 0.0, 1.0));
            m.reject_unknown_keys();
            const float sum = c.mix.walk + c.mix.idle + c.mix.reach;
            if (sum <= 0.0f) m.error("", "mix fractions must not all be zero");
            else c.mix.walk /= sum, c.mix.idle /= sum, c.mix.reach /= sum;
        }
        auto range = [&](const char* key, float& lo, float& hi, double min, double max) {
            const nlohmann::json* v = r.child(key);
            if (!v) return;
            if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number()) {
                r.error(key, "expected [min, max]");
                return;
            }
            const double a = (*v)[0].get<double>(), b = (*v)[1].get<double>();
            if (!(a >= min && b <= max && a <= b)) {
                r.error(key, "range must satisfy " + std::to_string(min) + " <= min <= max <= " + std::to_string(max));
                return;
            }
            lo = static_cast<float>(a), hi = static_cast<float>(b);
        };
        range("importance", c.importance_min, c.importance_max, 0.0, 1.0);
        range("speed", c.speed_min, c.speed_max, 0.0, 10.0);
        range("height", c.height_min, c.height_max, 0.5, 2.5);
        range("build", c.build_min, c.build_max, 0.0, 1.0);
        const bool varied = r.has("height") || r.has("build");
        c.variants = static_cast<uint32_t>(r.integer("variants", varied ? 6 : 0, 0, 64));
        if (c.variants > 0 && !varied) r.error("variants", "body variants need a 'height' or 'build' range");
        if (varied && c.variants == 0) r.error("variants", "a 'height' or 'build' range needs at least one variant");
        r.reject_unknown_keys();
        scene.crowds.push_back(c);
    }
}

}  // namespace aloha
