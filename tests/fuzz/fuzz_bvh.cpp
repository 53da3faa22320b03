// libFuzzer target: BVH motion capture (parse_bvh), with and without kept End Sites.
#include "engine/assets/bvh_loader.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    for (const bool keep_end_sites : {false, true}) {
        aloha::BvhOptions options;
        options.keep_end_sites = keep_end_sites;
        aloha::Result<aloha::BvhData> bvh = aloha::parse_bvh(text, "fuzz.bvh", options);
        if (!bvh.ok()) {
            if (bvh.error().file.empty()) __builtin_trap();  // every error must name the file
            continue;
        }
        // A parsed file has a skeleton and one track per joint.
        const aloha::BvhData& d = bvh.value();
        if (d.skeleton.joints.empty() || d.frame_count < 1) __builtin_trap();
    }
    return 0;
}
