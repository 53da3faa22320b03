// Test helper: Draco encoding for gltf_draco_test.cpp, in a shared library of its own that exports only these
// functions (engine/assets/CMakeLists.txt says why Draco is kept out of sight: it bundles a tinygltf and an
// stb_image of its own). No Draco type appears here.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#define ALOHA_TEST_DRACO_API __attribute__((visibility("default")))

namespace aloha::test {

/// Quantisation bits of the encoded attributes (Draco quantises each over its bounding box's largest extent).
struct DracoBits {
    int position = 14, normal = 10, texcoord = 12, generic = 10;  ///< generic: the float weights (integer joints stay exact)
};

/// An encoded mesh: its bytes, the unique ids of its attributes and what a decoder gets back.
struct DracoEncoded {
    std::vector<unsigned char> bytes;
    int position = -1, normal = -1, texcoord = -1, joints = -1, weights = -1;
    uint32_t points = 0, faces = 0;
    std::string error;  ///< "" when encoding and decoding back worked
};

/// Encodes a triangle mesh (positions, normals, texture coordinates float; joints as 4 unsigned shorts a
/// vertex; weights float) with `bits`.
ALOHA_TEST_DRACO_API DracoEncoded encode_draco_mesh(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                                                    const std::vector<glm::vec2>& uvs, const std::vector<uint16_t>& joints,
                                                    const std::vector<glm::vec4>& weights, const std::vector<uint16_t>& indices, const DracoBits& bits);

/// Encodes `positions` as a Draco point cloud (no faces); empty bytes on failure.
ALOHA_TEST_DRACO_API std::vector<unsigned char> encode_draco_point_cloud(const std::vector<glm::vec3>& positions, const DracoBits& bits);

}  // namespace aloha::test
