// skin_bake: skin layers and surface maps written and read back bit for bit; payloads that are cut
// short, padded or inconsistent (indices or influences out of range) read as nothing; keys differ
// with every parameter and input.
#include "systems/geometry/controller/skin_bake.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace aloha {
namespace {

// A small layer whose floats include -0 and a NaN with a payload (bits a value comparison would not see).
SkinLayer sample_layer() {
    SkinLayer l;
    l.theta_steps = 8;
    l.phi_steps = 6;
    l.rest_positions = {{0.0f, 1.0f, 2.0f}, {-0.0f, 0.5f, 0.25f}, {1.0f, std::nanf("7"), 3.0f}};
    l.rest_normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
    l.indices = {0, 1, 2, 2, 1, 0};
    l.bindings.resize(3);
    for (size_t v = 0; v < 3; ++v) {
        l.bindings[v].muscle[0] = static_cast<uint32_t>(v);
        l.bindings[v].param[1] = {0.25f * static_cast<float>(v), -1.0f};
        l.bindings[v].cell[2].corner[3] = 11;
        l.bindings[v].cell[2].ft = 0.75f;
        l.bindings[v].offset[3] = {1e-7f, -2.0f, 3.5f};
        l.bindings[v].weight[0] = 1.0f;
    }
    l.dominant_muscle = {0, 1, 2};
    l.joints = {{0, 1, 2, 3}, {4, 5, 6, 7}, {8, 9, 10, 11}};
    l.weights = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {0.25f, 0.25f, 0.25f, 0.25f}};
    return l;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(SkinBake, SkinLayerRoundTripIsBitIdentical) {
    const SkinLayer l = sample_layer();
    const std::vector<uint8_t> bytes = write_skin_layer(l);
    const std::optional<SkinLayer> r = read_skin_layer(bytes, 3);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->theta_steps, 8u);
    EXPECT_EQ(r->phi_steps, 6u);
    EXPECT_TRUE(same_bits(r->rest_positions, l.rest_positions));
    EXPECT_TRUE(same_bits(r->rest_normals, l.rest_normals));
    EXPECT_TRUE(same_bits(r->indices, l.indices));
    EXPECT_TRUE(same_bits(r->bindings, l.bindings));
    EXPECT_TRUE(same_bits(r->dominant_muscle, l.dominant_muscle));
    EXPECT_TRUE(same_bits(r->joints, l.joints));
    EXPECT_TRUE(same_bits(r->weights, l.weights));
    EXPECT_EQ(write_skin_layer(*r), bytes);
}

TEST(SkinBake, DamagedOrInconsistentSkinLayersReadAsNothing) {
    const std::vector<uint8_t> bytes = write_skin_layer(sample_layer());
    for (const size_t cut : {size_t{0}, size_t{5}, bytes.size() / 2, bytes.size() - 1})
        EXPECT_FALSE(read_skin_layer(std::span<const uint8_t>(bytes).first(cut), 3)) << cut << " bytes";
    std::vector<uint8_t> padded = bytes;
    padded.push_back(0);
    EXPECT_FALSE(read_skin_layer(padded, 3));
    EXPECT_FALSE(read_skin_layer(bytes, 2));  // muscle 2 is out of range for 2 muscles
    SkinLayer bad = sample_layer();
    bad.indices[4] = 3;  // a vertex past the three
    EXPECT_FALSE(read_skin_layer(write_skin_layer(bad), 3));
    bad = sample_layer();
    bad.rest_normals.pop_back();  // sizes per vertex disagree
    EXPECT_FALSE(read_skin_layer(write_skin_layer(bad), 3));
}

TEST(SkinBake, SurfaceMapRoundTripAndChecks) {
    SurfaceMap m;
    m.corners = {{0, 1, 2}, {2, 1, 0}};
    m.bary = {{0.2f, 0.3f, 0.5f}, {1.0f, -0.0f, 0.0f}};
    const std::vector<uint8_t> bytes = write_surface_map(m);
    const std::optional<SurfaceMap> r = read_surface_map(bytes, 3, 2);
    ASSERT_TRUE(r);
    EXPECT_TRUE(same_bits(r->corners, m.corners));
    EXPECT_TRUE(same_bits(r->bary, m.bary));
    EXPECT_FALSE(read_surface_map(bytes, 2, 2));  // corner 2 out of range
    EXPECT_FALSE(read_surface_map(bytes, 3, 3));  // another target count
    EXPECT_FALSE(read_surface_map(std::span<const uint8_t>(bytes).first(bytes.size() - 4), 3, 2));
}

TEST(SkinBake, TriangleListRoundTripAndChecks) {
    const std::vector<uint32_t> list = {0, 1, 2, 2, 1, 3};
    const std::vector<uint8_t> bytes = write_triangle_list(list);
    const std::optional<std::vector<uint32_t>> r = read_triangle_list(bytes, 4);
    ASSERT_TRUE(r);
    EXPECT_EQ(*r, list);
    EXPECT_FALSE(read_triangle_list(bytes, 3));  // vertex 3 out of range
    EXPECT_FALSE(read_triangle_list(write_triangle_list(std::span(list).first(5)), 4));  // not whole triangles
    EXPECT_FALSE(read_triangle_list(std::span<const uint8_t>(bytes).first(bytes.size() - 4), 4));
}

TEST(SkinBake, KeysDifferWithEveryParameterAndInput) {
    const std::vector<uint8_t> a = {1, 2, 3}, b = {1, 2, 4};
    EXPECT_NE(skin_layer_key(a, 8, 6), skin_layer_key(b, 8, 6));
    EXPECT_NE(skin_layer_key(a, 8, 6), skin_layer_key(a, 6, 8));
    // A surface map's key is the digest of what map_surface reads: the source, its triangles, the targets.
    const std::vector<glm::vec3> source = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, target = {{0.2f, 0.2f, 0.1f}};
    const std::vector<uint32_t> triangle = {0, 1, 2}, flipped = {0, 2, 1};
    const std::vector<uint8_t> key = surface_map_key(source, triangle, target);
    EXPECT_EQ(surface_map_key(source, triangle, target), key);
    std::vector<glm::vec3> moved = source;
    moved[2].y = 1.0000001f;
    EXPECT_NE(surface_map_key(moved, triangle, target), key);
    EXPECT_NE(surface_map_key(source, flipped, target), key);
    EXPECT_NE(surface_map_key(source, triangle, moved), key);
    EXPECT_NE(surface_map_key(target, triangle, source), key) << "source and target are not interchangeable";
    // A simplified list's key: the positions, the triangles and the bound.
    const std::vector<uint8_t> simple = simplified_indices_key(source, triangle, 0.006f);
    EXPECT_EQ(simplified_indices_key(source, triangle, 0.006f), simple);
    EXPECT_NE(simplified_indices_key(source, triangle, 0.012f), simple);
    EXPECT_NE(simplified_indices_key(moved, triangle, 0.006f), simple);
    EXPECT_NE(simplified_indices_key(source, flipped, 0.006f), simple);
    EXPECT_NE(simplified_indices_key(source, triangle, 0.006f), surface_map_key(source, triangle, {})) << "kinds differ";
    EXPECT_EQ(skin_layer_key(a, 8, 6), skin_layer_key(a, 8, 6));
    auto version = skin_bake_code_version();
    ASSERT_TRUE(version.ok()) << version.error().to_string();
    EXPECT_GE(version.value().size(), 21u);  // at least this program's own id and its length
}

}  // namespace
}  // namespace aloha
