// Shared helpers for the World tests.
#pragma once

#include "host/scene/world.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace aloha::scene_test {

/// Builds a World for `s` with `o`; fails the current test (returning null) when it cannot.
inline std::unique_ptr<World> make_world(const SceneDesc& s, WorldOptions o = {}) {
    auto w = World::create(s, o);
    EXPECT_TRUE(w.ok()) << (w.ok() ? "" : w.error().to_string());
    return w.ok() ? std::move(w.value()) : nullptr;
}

}  // namespace aloha::scene_test
