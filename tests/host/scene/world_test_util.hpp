// Shared helpers for the World tests.
#pragma once

#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace aloha::scene_test {

/// Parses `json` as the scene file `file`; fails the current test (returning an empty scene) when it cannot.
inline SceneDesc scene_from_json(const std::string& json, const std::string& file) {
    auto scene = parse_scene(json, file);
    EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().to_string());
    return scene.ok() ? scene.value() : SceneDesc{};
}

/// Builds a World for `s` with `o`; fails the current test (returning null) when it cannot.
inline std::unique_ptr<World> make_world(const SceneDesc& s, WorldOptions o = {}) {
    auto w = World::create(s, o);
    EXPECT_TRUE(w.ok()) << (w.ok() ? "" : w.error().to_string());
    return w.ok() ? std::move(w.value()) : nullptr;
}

}  // namespace aloha::scene_test
