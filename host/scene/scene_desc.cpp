#include "host/scene/scene_desc.hpp"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {

namespace {

// splitmix64: small, fast, fully deterministic across platforms.
struct SplitMix {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float uniform(float lo, float hi) {  // [lo, hi)
        const float u = static_cast<float>(next() >> 40) * (1.0f / 16777216.0f);
        return lo + (hi - lo) * u;
    }
};

}  // namespace

CameraKey sample_camera(const CameraDesc& camera, float t) {
    const auto& k = camera.keys;
    if (k.size() == 1 || t <= k.front().time) return k.front();
    if (t >= k.back().time) return k.back();
    size_t i = 1;
    while (k[i].time < t) ++i;
    const float a = (t - k[i - 1].time) / (k[i].time - k[i - 1].time);
    CameraKey out;
    out.time = t;
    out.position = glm::mix(k[i - 1].position, k[i].position, a);
    out.target = glm::mix(k[i - 1].target, k[i].target, a);
    return out;
}

std::vector<glm::vec3> circle_route(const glm::vec3& center, const glm::vec3& start, float turn) {
    const glm::vec3 off = start - center;
    const float radius = std::max(kMinCircleRadius, std::hypot(off.x, off.z));
    const float from = std::atan2(off.z, off.x);
    std::vector<glm::vec3> points;
    points.reserve(kCircleRouteWaypoints);
    for (int k = 1; k <= kCircleRouteWaypoints; ++k) {
        const float a = from + turn * glm::two_pi<float>() * static_cast<float>(k) / kCircleRouteWaypoints;
        points.push_back(center + glm::vec3(radius * std::cos(a), 0.0f, radius * std::sin(a)));
    }
    return points;
}

size_t drop_unused_variants(SceneDesc& scene, std::vector<CharacterDesc>& chars) {
    std::vector<uint32_t> used(scene.types.size(), 0);
    for (const CharacterDesc& c : chars) used[static_cast<size_t>(c.type)]++;
    std::vector<int> renumbered(scene.types.size(), -1);
    std::vector<CharacterTypeDesc> kept;
    for (size_t t = 0; t < scene.types.size(); ++t) {
        if (used[t] == 0 && !scene.types[t].variant_of.empty()) continue;
        renumbered[t] = static_cast<int>(kept.size());
        kept.push_back(std::move(scene.types[t]));
    }
    const size_t dropped = scene.types.size() - kept.size();
    scene.types = std::move(kept);
    if (dropped == 0) return 0;
    const auto renumber = [&](int& type) {
        assert(type >= 0 && renumbered[static_cast<size_t>(type)] >= 0);  // only unused variants are dropped
        type = renumbered[static_cast<size_t>(type)];
    };
    for (CharacterDesc& c : chars) renumber(c.type);
    for (CharacterDesc& c : scene.characters) renumber(c.type);
    for (CrowdDesc& crowd : scene.crowds) {
        renumber(crowd.type);  // a base type is no variant: never dropped
        for (int& v : crowd.variant_types) v = v >= 0 ? renumbered[static_cast<size_t>(v)] : -1;
    }
    return dropped;
}

uint64_t character_count(const SceneDesc& scene) {
    uint64_t n = scene.characters.size();
    for (const auto& c : scene.crowds) n += c.count;
    return n;
}

std::vector<CharacterDesc> expand_characters(const SceneDesc& scene, uint64_t seed_override) {
    std::vector<CharacterDesc> out = scene.characters;
    out.reserve(static_cast<size_t>(character_count(scene)));
    for (size_t ci = 0; ci < scene.crowds.size(); ++ci) {
        const CrowdDesc& crowd = scene.crowds[ci];
        SplitMix rng{(seed_override ? seed_override : crowd.seed) * 0x100000001B3ull + ci};
        const uint32_t side = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(crowd.count))));
        for (uint32_t i = 0; i < crowd.count; ++i) {
            CharacterDesc c;
            c.type = crowd.type;
            if (!crowd.variant_types.empty()) {
                c.type = crowd.variant_types[static_cast<size_t>(rng.next() % crowd.variant_types.size())];
                assert(c.type >= 0 && "a variant drop_unused_variants dropped, picked with another seed");
            }
            if (crowd.layout == CrowdDesc::Layout::Grid) {
                const float x = (static_cast<float>(i % side) - 0.5f * static_cast<float>(side - 1)) * crowd.spacing;
                const float z = (static_cast<float>(i / side) - 0.5f * static_cast<float>(side - 1)) * crowd.spacing;
                c.position = crowd.center + glm::vec3(x, 0.0f, z);
            } else {
                const float r = crowd.radius * std::sqrt(rng.uniform(0.0f, 1.0f));
                const float a = rng.uniform(0.0f, glm::two_pi<float>());
                c.position = crowd.center + glm::vec3(r * std::cos(a), 0.0f, r * std::sin(a));
            }
            c.heading_deg = rng.uniform(0.0f, 360.0f);
            c.importance = rng.uniform(crowd.importance_min, crowd.importance_max);
            const float pick = rng.uniform(0.0f, 1.0f);
            RequestDesc req;
            if (pick < crowd.mix.walk) {
                req.request.kind = RequestKind::Walk;
                req.request.speed = rng.uniform(crowd.speed_min, crowd.speed_max);
                if (crowd.walk_route == CrowdDesc::WalkRoute::Circle) {
                    // Alternate walkers turn opposite ways; each starts facing along its circle.
                    const float turn = i % 2 == 0 ? 1.0f : -1.0f;
                    req.route = circle_route(crowd.center, c.position, turn);
                    const glm::vec3 along = req.route.front() - c.position;
                    if (glm::length(glm::vec2(along.x, along.z)) > 1e-4f)
                        c.heading_deg = glm::degrees(std::atan2(along.x, along.z));
                }
                const float h = glm::radians(c.heading_deg);
                req.request.target = glm::vec3(std::sin(h), 0.0f, std::cos(h));
            } else if (pick < crowd.mix.walk + crowd.mix.idle) {
                req.request.kind = RequestKind::PlayClip;
                req.request.loop = 1;
                req.request.start_time = rng.uniform(0.0f, 8.0f);
                req.clip = crowd.clip;
            } else {
                req.request.kind = RequestKind::Reach;
                req.effector = rng.uniform(0.0f, 1.0f) < 0.5f ? "RightWrist" : "LeftWrist";
                req.request.target = c.position + glm::vec3(rng.uniform(-0.5f, 0.5f), rng.uniform(0.9f, 1.6f), rng.uniform(-0.5f, 0.5f));
            }
            c.requests.push_back(req);
            out.push_back(std::move(c));
        }
    }
    return out;
}

}  // namespace aloha
