// Hardware tiers: "default_tier": "auto" picks from the hardware (software rasteriser, cores, GPU
// memory) by a built-in policy or by the tiers' own requirements; a named tier (host or scene) and a
// named default_tier win over it.
#include "systems/lod/tier.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using lod_test::must_parse;
using lod_test::small_rules;
using nlohmann::json;

json three_tiers(const json& default_tier) {
    json j = small_rules();
    j["tiers"] = {"low", "medium", "high"};
    j["default_tier"] = default_tier;
    return j;
}

HardwareInfo machine(unsigned cores, uint64_t gpu_mb, bool software) {
    HardwareInfo hw;
    hw.cores = cores;
    hw.gpu_memory_mb = gpu_mb;
    hw.software_rasterizer = software;
    hw.gpu_name = software ? "llvmpipe (LLVM 15.0.6, 256 bits)" : "Some GPU";
    return hw;
}

TEST(Tier, AutoFollowsTheHardware) {
    const RuleTable t = must_parse(three_tiers("auto"));
    EXPECT_TRUE(t.tier_auto);
    auto name = [&](const HardwareInfo& hw) { return t.tiers[resolve_tier(t, -1, &hw).tier]; };
    EXPECT_EQ(name(machine(2, 0, true)), "low");        // software rasteriser
    EXPECT_EQ(name(machine(32, 0, true)), "low");       // however many cores
    EXPECT_EQ(name(machine(2, 8192, false)), "low");    // a GPU but only 2 cores
    EXPECT_EQ(name(machine(4, 2048, false)), "medium");
    EXPECT_EQ(name(machine(8, 2048, false)), "medium"); // cores but little GPU memory
    EXPECT_EQ(name(machine(8, 4096, false)), "high");
    const TierChoice c = resolve_tier(t, -1, nullptr);  // no facts: the richest
    EXPECT_EQ(t.tiers[c.tier], "high");
    EXPECT_NE(c.reason.find("no hardware facts"), std::string::npos) << c.reason;
    const HardwareInfo soft = machine(2, 0, true);
    EXPECT_NE(resolve_tier(t, -1, &soft).reason.find("software rasteriser (llvmpipe"), std::string::npos);
}

TEST(Tier, NamedTiersWin) {
    const RuleTable t = must_parse(three_tiers("auto"));
    const HardwareInfo soft = machine(2, 0, true);
    EXPECT_EQ(resolve_tier(t, 2, &soft).tier, 2);  // the host or the scene named "high"
    const RuleTable fixed = must_parse(three_tiers("medium"));
    EXPECT_FALSE(fixed.tier_auto);
    const HardwareInfo big = machine(64, 80000, false);
    EXPECT_EQ(resolve_tier(fixed, -1, &big).tier, 1);  // the file's named default_tier
    EXPECT_EQ(resolve_tier(fixed, 0, &big).tier, 0);
}

TEST(Tier, TheFilesRequirementsDecide) {
    json j = three_tiers("auto");
    j["tiers"] = json::array({"low",
                              {{"name", "medium"}, {"min_cores", 2}, {"needs_hardware_gpu", true}},
                              {{"name", "high"}, {"min_cores", 8}, {"min_gpu_memory_mb", 16000}}});
    const RuleTable t = must_parse(j);
    ASSERT_EQ(t.tiers.size(), 3u);
    EXPECT_TRUE(t.tier_requirements_given);
    EXPECT_EQ(t.tier_requirements[1].min_cores, 2u);
    auto pick = [&](const HardwareInfo& hw) { return t.tiers[auto_tier(t, hw).tier]; };
    EXPECT_EQ(pick(machine(16, 0, true)), "low");          // medium needs a hardware GPU
    EXPECT_EQ(pick(machine(2, 4096, false)), "medium");
    EXPECT_EQ(pick(machine(16, 8192, false)), "medium");   // high needs 16 GB
    EXPECT_EQ(pick(machine(16, 16384, false)), "high");
    // "high" with no requirement of a hardware GPU: a big machine with a software rasteriser qualifies
    // for it even though it does not for "medium" (each tier is judged by its own requirements).
    EXPECT_EQ(pick(machine(16, 16384, true)), "high");
}

TEST(Tier, BadTierSectionsAreRefused) {
    auto errors_of = [](const json& j) {
        std::vector<Error> errors;
        EXPECT_FALSE(parse_rules(j.dump(2), "tiers.json", &errors).ok());
        return join_errors(errors);
    };
    EXPECT_NE(errors_of(three_tiers("ultra")).find("/default_tier: unknown tier \"ultra\""), std::string::npos);
    json j = three_tiers("auto");
    j["tiers"][1] = {{"name", "medium"}, {"min_core", 2}};
    EXPECT_NE(errors_of(j).find("/tiers/1/min_core: unknown key"), std::string::npos);
    j = three_tiers("auto");
    j["tiers"][2] = 3;
    EXPECT_NE(errors_of(j).find("/tiers/2: expected a tier name"), std::string::npos);
    j = three_tiers("auto");
    j["tiers"][2] = "low";
    EXPECT_NE(errors_of(j).find("duplicate tier"), std::string::npos);
}

}  // namespace
}  // namespace aloha
