// Volume preservation measured on the muscle surface the controller actually draws: every muscle's
// tessellated 24 x 16 mesh of the built-in humanoid encloses (divergence theorem) its rest volume
// within 2 % while both elbows and knees sweep 0-140 degrees.
#include "systems/geometry/surface_grid.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"
#include "tests/systems/geometry/muscle/grid_volume.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace aloha {
namespace {

// Model matrices of `s` at its rest pose with each elbow flexed by `angle` (forearm forwards, about the
// lateral x axis) and each knee by `angle` (shin backwards).
std::vector<glm::mat4> flexed(const Skeleton& s, float angle) {
    std::vector<glm::mat4> m(static_cast<size_t>(s.joint_count()));
    for (size_t j = 0; j < m.size(); ++j) {
        const std::string& name = s.names()[j];
        glm::quat r = s.rest_rotations()[j];
        if (name == "LeftElbow" || name == "RightElbow") r = r * glm::angleAxis(-angle, glm::vec3(1, 0, 0));
        if (name == "LeftKnee" || name == "RightKnee") r = r * glm::angleAxis(angle, glm::vec3(1, 0, 0));
        const glm::mat4 local = glm::translate(glm::mat4(1.0f), s.rest_translations()[j]) * glm::mat4_cast(r);
        m[j] = s.parents()[j] < 0 ? local : m[static_cast<size_t>(s.parents()[j])] * local;
    }
    return m;
}

TEST(MuscleVolume, DrawnMusclesKeepTheirVolumeAsElbowsAndKneesFlex) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    const CharacterGeometry& g = *h.geometry;
    const std::vector<GeomLod> levels = {test::grid_level(GeomMethod::Layered, 24, 16)};
    GeometryController ctl(g, levels, 1);
    ctl.begin_level(0, 0, -1, 0);
    const uint32_t c = 0, M = g.muscle_count();
    std::vector<double> rest(M);
    std::vector<glm::vec3> surface;
    double worst = 0.0;
    std::string worst_at;
    for (int deg = 0; deg <= 140; deg += 10) {
        const auto pose = flexed(g.skeleton(), glm::radians(static_cast<float>(deg)));
        ctl.update(0, std::span(&c, 1), PoseSource{pose.data(), 0}, 1.0f / 30.0f);
        ctl.muscle_surface(0, surface);
        ASSERT_EQ(surface.size(), size_t{M} * grid_vertex_count(24, 16));
        for (uint32_t m = 0; m < M; ++m) {
            const double v = test::grid_volume(surface, 24, 16, m);
            if (deg == 0) {
                ASSERT_GT(v, 0.0) << g.muscles().names[m];
                rest[m] = v;
                continue;
            }
            const double err = std::abs(v / rest[m] - 1.0);
            if (err > worst) worst = err, worst_at = g.muscles().names[m] + " at " + std::to_string(deg) + " degrees";
            EXPECT_LT(err, 0.02) << g.muscles().names[m] << " at " << deg << " degrees";
        }
    }
    std::cout << "largest drawn-volume change: " << worst * 100.0 << " % (" << worst_at << ")\n";
}

}  // namespace
}  // namespace aloha
