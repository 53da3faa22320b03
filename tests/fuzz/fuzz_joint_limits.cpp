// libFuzzer target: joint-limit tables (parse_joint_limits).
#include "engine/assets/joint_limits.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    aloha::Result<aloha::JointLimitTable> t = aloha::parse_joint_limits(text, "fuzz_limits.json");
    if (!t.ok()) {
        if (t.error().file.empty()) __builtin_trap();  // every error must name the file
        return 0;
    }
    if (t.value().names.size() != t.value().limits.size()) __builtin_trap();
    return 0;
}
