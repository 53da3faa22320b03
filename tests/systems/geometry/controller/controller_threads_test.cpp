// Concurrent update of disjoint characters (same and different levels) equals a serial run, bit for bit.
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <thread>

namespace aloha {
namespace {

using test::humanoid;

constexpr uint32_t kCharacters = 20;
constexpr uint8_t kLevels = 5;  // levels 0..4 of test_levels() (every method but Hidden)

// Poses of every character at frame f (each character at its own key of the clip), stride = joints.
std::vector<glm::mat4> crowd_pose(const CharacterGeometry& g, size_t f) {
    std::vector<glm::mat4> all;
    for (uint32_t c = 0; c < kCharacters; ++c) {
        const auto p = test::clip_pose(g.skeleton(), humanoid().clip, 40 * c + 3 * f);
        all.insert(all.end(), p.begin(), p.end());
    }
    return all;
}

// Characters of `level` whose id has parity `parity` (threads split each level's list in two).
std::vector<uint32_t> members(const GeometryController& ctl, uint8_t level, int parity) {
    std::vector<uint32_t> out;
    for (uint32_t c = 0; c < kCharacters; ++c)
        if (ctl.level_of(c) == level && (parity < 0 || static_cast<int>(c % 2) == parity)) out.push_back(c);
    return out;
}

// Runs 6 frames; at frame 3 every character moves one level down with a 4-frame morph.
void run(GeometryController& ctl, bool threaded) {
    const CharacterGeometry& g = ctl.geometry();
    for (uint32_t c = 0; c < kCharacters; ++c) ctl.begin_level(c, static_cast<uint8_t>(c % kLevels), -1, 0);
    for (size_t f = 0; f < 6; ++f) {
        if (f == 3)
            for (uint32_t c = 0; c < kCharacters; ++c)
                ctl.begin_level(c, static_cast<uint8_t>((c + 1) % kLevels), static_cast<int8_t>(c % kLevels), 4);
        const auto poses = crowd_pose(g, f);
        const PoseSource src{poses.data(), g.joint_count()};
        if (!threaded) {
            for (uint8_t l = 0; l < kLevels; ++l) {
                const auto list = members(ctl, l, -1);
                ctl.update(l, list, src, 1.0f / 30.0f);
            }
            continue;
        }
        // Thread A: even ids of every level, thread B: odd ids, levels visited in opposite orders so
        // the two threads work on different levels and on the same level at once.
        auto worker = [&](int parity) {
            for (uint8_t k = 0; k < kLevels; ++k) {
                const uint8_t l = parity == 0 ? k : static_cast<uint8_t>(kLevels - 1 - k);
                const auto list = members(ctl, l, parity);
                ctl.update(l, list, src, 1.0f / 30.0f);
            }
        };
        std::thread a(worker, 0), b(worker, 1);
        a.join();
        b.join();
    }
}

TEST(GeometryControllerThreads, ConcurrentDisjointUpdatesEqualSerial) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    const auto levels = test::test_levels();
    GeometryController serial(g, levels, kCharacters), threaded(g, levels, kCharacters);
    run(serial, false);
    run(threaded, true);
    for (uint32_t c = 0; c < kCharacters; ++c) {
        SCOPED_TRACE(c);
        const SurfaceView a = serial.surface(c), b = threaded.surface(c);
        ASSERT_EQ(a.level, b.level);
        ASSERT_EQ(a.positions.size(), b.positions.size());
        ASSERT_EQ(a.normals.size(), b.normals.size());
        if (!a.positions.empty()) {
            EXPECT_EQ(std::memcmp(a.positions.data(), b.positions.data(), a.positions.size_bytes()), 0);
            EXPECT_EQ(std::memcmp(a.normals.data(), b.normals.data(), a.normals.size_bytes()), 0);
        }
        const auto pa = serial.proxy_boxes(c), pb = threaded.proxy_boxes(c);
        ASSERT_EQ(pa.size(), pb.size());
        if (!pa.empty()) {
            EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size_bytes()), 0);
        }
        EXPECT_EQ(serial.geomorph_frames_left(c), threaded.geomorph_frames_left(c));
    }
}

}  // namespace
}  // namespace aloha
