// Draco mesh decoding behind a shared library of its own (aloha::draco, libaloha_draco.so). Debian's
// libdraco bundles its own tinygltf, stb_image and nlohmann-json: linked into a program beside the loader's
// libtinygltf and stb, those copies replace the loader's and crash it. libaloha_draco.so links Draco
// statically and exports only decode_draco_mesh(), so none of Draco's copies is visible outside it, and
// this header names no Draco type.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#if defined(__GNUC__)
#define ALOHA_DRACO_API __attribute__((visibility("default")))
#else
#define ALOHA_DRACO_API
#endif

namespace aloha {

/// One attribute of a decoded Draco mesh, per point (after Draco's point-to-value mapping).
struct DracoAttribute {
    uint32_t unique_id = 0;     ///< the id glTF's KHR_draco_mesh_compression `attributes` refer to
    int components = 0;         ///< values per point (1 to 4)
    int gltf_component = 0;     ///< glTF componentType of Draco's stored type (5120-5126), 0 when glTF has none
    bool normalized = false;    ///< Draco's flag: integers stand for [0, 1] (unsigned) or [-1, 1] (signed)
    uint64_t type_max = 0;      ///< largest value of the stored integer type (for `normalized`), 0 for floats
    std::vector<double> values; ///< points * components stored values, unnormalised (integers exactly)
};

/// A decoded Draco triangle mesh.
struct DracoMesh {
    size_t points = 0;
    std::vector<uint32_t> indices;           ///< 3 per triangle, each < points
    std::vector<DracoAttribute> attributes;  ///< every attribute the data holds
};

/// Decodes the Draco bytes `data[0, size)` into `out`. Returns "" on success, else why it failed (not
/// Draco data, a point cloud, a decoding error, a mesh of more than `max_values` points or indices, a
/// point mapped past its attribute's values). Never throws.
ALOHA_DRACO_API std::string decode_draco_mesh(const unsigned char* data, size_t size, size_t max_values, DracoMesh* out);

}  // namespace aloha
