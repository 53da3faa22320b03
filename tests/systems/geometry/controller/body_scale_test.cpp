// The generated body at any size (skin_layer.hpp: body_length_scale): a body k times a person's, built with its
// lengths times k, is the person's body times k, cell for cell; the scale is 1 over people's heights.
#include "systems/geometry/controller/skin_layer.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace aloha {
namespace {

TEST(BodyScale, OneForPeopleAndTheHeightBeyondTheirRange) {
    EXPECT_EQ(body_length_scale(0.5f), 1.0f);
    EXPECT_EQ(body_length_scale(1.75f), 1.0f);
    EXPECT_EQ(body_length_scale(2.5f), 1.0f);
    EXPECT_FLOAT_EQ(body_length_scale(12.5f), 5.0f);
    EXPECT_FLOAT_EQ(body_length_scale(0.125f), 0.25f);
    EXPECT_EQ(body_length_scale(0.0f), 1.0f) << "unknown height";
    EXPECT_EQ(body_length_scale(-1.0f), 1.0f);
    EXPECT_EQ(body_length_scale(std::numeric_limits<float>::quiet_NaN()), 1.0f);
    EXPECT_EQ(body_length_scale(std::numeric_limits<float>::infinity()), 1.0f);
}

// The built-in humanoid at 1.75 m and at 6 x 1.75 m (skeleton, muscle lengths, girths and fat all 6x), the giant's
// body built with length_scale 6: the same grid (cells and their count), the signed distance 6x at every grid
// point, the polygonised surface's vertices 6x within float rounding. Before the scale, the giant's 8 mm grid had
// 216 times the cells.
TEST(BodyScale, AGiantsBodyIsThePersonsScaled) {
    constexpr float k = 6.0f;
    const test::Humanoid& h = test::humanoid();
    ASSERT_TRUE(h.geometry);
    const std::string def_path = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid.json";
    const std::string muscle_path = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid_muscles.json";
    auto def = load_humanoid_definition(def_path);
    ASSERT_TRUE(def.ok());
    auto skeleton = build_skeleton(humanoid_skeleton(def.value(), HumanoidBody{1.75f * k}), def_path);
    ASSERT_TRUE(skeleton.ok());
    auto defs = load_muscle_defs(muscle_path);
    ASSERT_TRUE(defs.ok());
    scale_muscle_defs(defs.value(), k, 1.0f, k);
    auto muscles = resolve_muscles(defs.value(), skeleton.value(), muscle_path);
    ASSERT_TRUE(muscles.ok()) << muscles.error().to_string();
    CharacterGeometryDesc desc;
    desc.name = "giant";
    desc.skeleton = std::move(skeleton).value();
    desc.muscles = std::move(muscles).value();
    desc.length_scale = k;
    auto giant = CharacterGeometry::create(std::move(desc));
    ASSERT_TRUE(giant.ok()) << giant.error().to_string();
    const CharacterGeometry& g = *giant.value();
    const CharacterGeometry& p = *h.geometry;
    ASSERT_EQ(g.proxy_radii().size(), p.proxy_radii().size());
    for (size_t j = 0; j < p.proxy_radii().size(); ++j) EXPECT_NEAR(g.proxy_radii()[j], k * p.proxy_radii()[j], 1e-5f * k);

    const BodySurface person_body = build_body_surface(p.muscles(), p.skeleton(), p.rest_model(), p.proxy_radii(), 1.0f);
    const BodySurface giant_body = build_body_surface(g.muscles(), g.skeleton(), g.rest_model(), g.proxy_radii(), k);
    ASSERT_EQ(giant_body.field.nx, person_body.field.nx);
    ASSERT_EQ(giant_body.field.ny, person_body.field.ny);
    ASSERT_EQ(giant_body.field.nz, person_body.field.nz);
    EXPECT_FLOAT_EQ(giant_body.field.cell, k * person_body.field.cell);
    // Distances: float rounding of values up to a few decimetres (6x: metres), relative 1e-5 of the grid's extent.
    const float extent = float(person_body.field.ny) * person_body.field.cell;
    float worst = 0.0f;
    for (size_t i = 0; i < person_body.field.values.size(); ++i)
        worst = std::max(worst, std::abs(giant_body.field.values[i] / k - person_body.field.values[i]));
    EXPECT_LT(worst, 1e-5f * extent) << "the signed distance scales with the body";
    ASSERT_EQ(giant_body.dense.indices.size(), person_body.dense.indices.size()) << "one topology";
    ASSERT_EQ(giant_body.dense.positions.size(), person_body.dense.positions.size());
    float moved = 0.0f;
    for (size_t i = 0; i < person_body.dense.positions.size(); ++i)
        moved = std::max(moved, glm::length(giant_body.dense.positions[i] / k - person_body.dense.positions[i]));
    // A vertex interpolates the zero crossing between two grid points: the distances' rounding over their
    // difference (at least ~1e-3 of a cell where a crossing is placed at all) stays well under a millimetre.
    EXPECT_LT(moved, 1e-4f) << "metres, person's scale";
}

}  // namespace
}  // namespace aloha
