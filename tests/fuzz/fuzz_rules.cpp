// libFuzzer target: LOD rule files (parse_rules), with every error collected.
#include "systems/lod/rule_table.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::vector<aloha::Error> all;
    aloha::Result<aloha::RuleTable> table = aloha::parse_rules(text, "fuzz_rules.json", &all);
    if (!table.ok() && table.error().file.empty()) __builtin_trap();  // every error must name the file
    if (table.ok()) {
        // The documented invariants of a loaded table.
        const aloha::RuleTable& t = table.value();
        if (t.geom_levels.empty() || t.anim_levels.empty() || t.rules.empty()) __builtin_trap();
        if (t.compiled.size() != t.rules.size() || !t.rules.back().unconditional) __builtin_trap();
        for (const aloha::CompiledRule& c : t.compiled)
            if (c.geom_level >= t.geom_levels.size() || c.anim_level >= t.anim_levels.size() ||
                size_t{c.first_box} + c.box_count > t.boxes.size())
                __builtin_trap();
    }
    return 0;
}
