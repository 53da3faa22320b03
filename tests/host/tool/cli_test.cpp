#include "host/tool/cli_args.hpp"

#include <gtest/gtest.h>

namespace aloha::tool {
namespace {

Result<CliOptions> parse(std::vector<std::string> args) { return parse_cli(args); }

TEST(Cli, ParsesProfileOptions) {
    auto r = parse({"profile", "scene.json", "--frames", "120", "--warmup=5", "--out", "dir", "--lod", "off",
                    "--budget-ms", "12.5", "--threads", "2", "--seed", "9", "--characters", "2000", "--fidelity"});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const CliOptions& o = r.value();
    EXPECT_EQ(o.command, "profile");
    EXPECT_EQ(o.scene, "scene.json");
    EXPECT_EQ(*o.frames, 120u);
    EXPECT_EQ(o.warmup, 5u);
    EXPECT_EQ(o.out, "dir");
    EXPECT_FALSE(o.lod);
    EXPECT_DOUBLE_EQ(*o.budget_ms, 12.5);
    EXPECT_EQ(o.threads, 2u);
    EXPECT_EQ(*o.seed, 9u);
    EXPECT_EQ(*o.characters, 2000u);
    EXPECT_TRUE(o.fidelity);
    EXPECT_FALSE(o.max_texture_side) << "unset: the renderer's default";
    EXPECT_FALSE(o.impostor_elevations) << "unset: the world's default";
    EXPECT_FALSE(o.impostor_views) << "unset: by device";
    EXPECT_FALSE(o.far_layer_alpha_test) << "unset: the renderer's default";
    auto t = parse({"render", "scene.json", "--texture-max", "512", "--impostor-elevations", "1", "--impostor-views", "nearest",
                    "--far-layer-alpha", "50"});
    ASSERT_TRUE(t.ok()) << t.error().to_string();
    EXPECT_EQ(t.value().max_texture_side, 512u);
    EXPECT_EQ(t.value().impostor_elevations, 1u);
    EXPECT_FALSE(t.value().impostor_share_px) << "unset: the world's default";
    auto share = parse({"profile", "scene.json", "--impostor-share", "0.5"});
    ASSERT_TRUE(share.ok()) << share.error().to_string();
    EXPECT_FLOAT_EQ(*share.value().impostor_share_px, 0.5f);
    for (const char* bad : {"-1", "97", "x"}) {
        auto refused = parse({"profile", "scene.json", "--impostor-share", bad});
        ASSERT_FALSE(refused.ok()) << bad;
        EXPECT_NE(refused.error().to_string().find("--impostor-share"), std::string::npos) << refused.error().to_string();
    }
    EXPECT_EQ(t.value().impostor_views, ImpostorViews::Nearest);
    for (const auto& [word, views] : {std::pair{"blend", ImpostorViews::Blend}, std::pair{"pick", ImpostorViews::Pick}}) {
        auto v = parse({"profile", "scene.json", "--impostor-views", word});
        ASSERT_TRUE(v.ok()) << v.error().to_string();
        EXPECT_EQ(v.value().impostor_views, views) << word;
    }
    EXPECT_FLOAT_EQ(*t.value().far_layer_alpha_test, 0.5f);
}

TEST(Cli, ParsesBudgetTierAndOcclusionOptions) {
    auto r = parse({"profile", "scene.json", "--budget", "off", "--budget-animation-ms", "1.5", "--budget-geometry-ms",
                    "4", "--budget-single-ms", "6", "--tier", "medium", "--occlusion", "off"});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const CliOptions& o = r.value();
    ASSERT_TRUE(o.budget.has_value());
    EXPECT_FALSE(*o.budget);
    EXPECT_DOUBLE_EQ(*o.budget_animation_ms, 1.5);
    EXPECT_DOUBLE_EQ(*o.budget_geometry_ms, 4.0);
    EXPECT_DOUBLE_EQ(*o.budget_single_ms, 6.0);
    EXPECT_FALSE(o.budget_ms.has_value());
    EXPECT_EQ(o.tier, "medium");
    EXPECT_FALSE(o.occlusion);
    EXPECT_TRUE(o.cache);  // the bake cache is on by default, at the default directory
    EXPECT_TRUE(o.cache_dir.empty());
}

TEST(Cli, ParsesBakeCacheOptions) {
    auto on = parse({"render", "s.json", "--cache-dir", "/tmp/bakes"});
    ASSERT_TRUE(on.ok()) << on.error().to_string();
    EXPECT_TRUE(on.value().cache);
    EXPECT_EQ(on.value().cache_dir, "/tmp/bakes");
    EXPECT_FALSE(on.value().cache_max_bytes.has_value());  // the default limit ($ALOHA_CACHE_MAX_MB, else 1 GiB)
    auto limited = parse({"profile", "s.json", "--cache-max-mb", "256"});
    ASSERT_TRUE(limited.ok()) << limited.error().to_string();
    EXPECT_EQ(limited.value().cache_max_bytes, uint64_t{256} << 20);
    auto off = parse({"profile", "s.json", "--cache", "off"});
    ASSERT_TRUE(off.ok()) << off.error().to_string();
    EXPECT_FALSE(off.value().cache);
    auto d = parse({"profile", "scene.json"});
    ASSERT_TRUE(d.ok());
    EXPECT_FALSE(d.value().budget.has_value());  // the rule file decides
    EXPECT_TRUE(d.value().occlusion);
    EXPECT_TRUE(d.value().tier.empty());
    EXPECT_EQ(d.value().gpu_overlap, GpuOverlap::Auto);  // overlapped only while the GPU frame is long
    for (const auto& [name, mode] : {std::pair{"on", GpuOverlap::On}, std::pair{"off", GpuOverlap::Off}, std::pair{"auto", GpuOverlap::Auto}}) {
        auto g = parse({"profile", "scene.json", "--gpu-overlap", name});
        ASSERT_TRUE(g.ok()) << g.error().to_string();
        EXPECT_EQ(g.value().gpu_overlap, mode);
    }
}

TEST(Cli, RejectsBadArgumentsNamingThem) {
    struct Case { std::vector<std::string> args; std::string words; };
    const std::vector<Case> cases = {
        {{"fly", "s.json"}, "unknown command 'fly'"},
        {{"profile"}, "needs a scene file"},
        {{"profile", "s.json", "--frames"}, "'--frames' needs a value"},
        {{"profile", "s.json", "--frames", "ten"}, "'ten'"},
        {{"profile", "s.json", "--frames", "0"}, "[1, 10000000]"},
        {{"profile", "s.json", "--frames", "-3"}, "'-3'"},
        {{"profile", "s.json", "--lod", "maybe"}, "'--lod' expects on or off"},
        {{"profile", "s.json", "--budget-ms", "nan"}, "--budget-ms"},
        {{"profile", "s.json", "--budget-ms", "-1"}, "--budget-ms"},
        {{"profile", "s.json", "--budget-geometry-ms", "0"}, "'--budget-geometry-ms' expects"},
        {{"profile", "s.json", "--budget", "maybe"}, "'--budget' expects on or off"},
        {{"profile", "s.json", "--occlusion", "1"}, "'--occlusion' expects on or off"},
        {{"profile", "s.json", "--cache", "no"}, "'--cache' expects on or off"},
        {{"profile", "s.json", "--gpu-overlap", "yes"}, "'--gpu-overlap' expects"},
        {{"profile", "s.json", "--fidelity", "--gpu-overlap", "on"}, "cannot go with --gpu-overlap on"},
        {{"profile", "s.json", "--cache", "off", "--cache-dir", "d"}, "goes with --cache on"},
        {{"profile", "s.json", "--cache", "off", "--cache-max-mb", "5"}, "--cache-max-mb limits the bake cache"},
        {{"profile", "s.json", "--cache-max-mb", "lots"}, "'--cache-max-mb' expects"},
        {{"profile", "s.json", "--tier"}, "'--tier' needs a value"},
        {{"profile", "s.json", "--threads", "1000"}, "[0, 256]"},
        {{"profile", "s.json", "--frame", "3"}, "not known to 'aloha profile'"},
        {{"render", "s.json", "--warmup", "3"}, "not known to 'aloha render'"},
        {{"render", "s.json", "--colour", "pink"}, "'--colour' expects"},
        {{"render", "a.json", "b.json"}, "unexpected argument 'b.json'"},
        {{"profile", "s.json", "--width", "8"}, "[16, 8192]"},
        {{"render", "s.json", "--texture-max", "-1"}, "'-1'"},
        {{"render", "s.json", "--texture-max", "20000"}, "[0, 16384]"},
        {{"profile", "s.json", "--impostor-elevations", "9"}, "'--impostor-elevations' expects a whole number in [1, 8], got '9'"},
        {{"profile", "s.json", "--impostor-elevations", "0"}, "[1, 8]"},
        {{"view", "s.json", "--impostor-views", "mixed"}, "'--impostor-views'"},
        {{"profile", "s.json", "--far-layer-alpha", "0"}, "'--far-layer-alpha' expects a whole number in [1, 100]"},
    };
    for (const Case& c : cases) {
        auto r = parse(c.args);
        ASSERT_FALSE(r.ok()) << c.words;
        EXPECT_NE(r.error().to_string().find(c.words), std::string::npos) << r.error().to_string();
    }
}

TEST(Cli, ScaleTakesAListOfCounts) {
    auto r = parse({"scale", "s.json", "--counts", "1000,2000,5000", "--no-render"});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_EQ(r.value().counts, (std::vector<uint32_t>{1000, 2000, 5000}));
    for (const char* bad : {"1000,,2000", "1000,x", "0", "2000000", ""}) {
        auto b = parse({"scale", "s.json", "--counts", bad});
        EXPECT_FALSE(b.ok()) << bad;
    }
    EXPECT_FALSE(parse({"scale", "s.json"}).ok());  // --counts is required
    auto cmp = parse({"profile", "s.json", "--compare-lod", "--compare-frames", "4"});
    ASSERT_TRUE(cmp.ok());
    EXPECT_TRUE(cmp.value().compare_lod);
    EXPECT_EQ(cmp.value().compare_frames, 4u);
}

TEST(Cli, HelpEverywhere) {
    auto top = parse({"--help"});
    ASSERT_TRUE(top.ok());
    EXPECT_EQ(top.value().command, "help");
    for (const char* cmd : {"render", "view", "profile", "scale", "validate"}) {
        auto r = parse({cmd, "--help"});
        ASSERT_TRUE(r.ok()) << cmd;
        EXPECT_TRUE(r.value().help);
        EXPECT_NE(help_text(cmd).find(std::string("aloha ") + cmd), std::string::npos);
    }
}

}  // namespace
}  // namespace aloha::tool

namespace aloha::tool {
namespace {

TEST(Cli, ExportTakesJointsCharactersAndFrameRanges) {
    auto o = parse_cli({"export", "s.json", "--joints", "j.csv", "--characters", "0,5,10-20", "--frames", "30:90"});
    ASSERT_TRUE(o.ok()) << o.error().to_string();
    EXPECT_EQ(o.value().joints, "j.csv");
    const std::vector<std::pair<uint32_t, uint32_t>> ranges = {{0, 0}, {5, 5}, {10, 20}};
    EXPECT_EQ(o.value().character_ranges, ranges);
    ASSERT_TRUE(o.value().frame_range);
    EXPECT_EQ(*o.value().frame_range, (std::pair<uint32_t, uint32_t>{30, 90}));
    auto n = parse_cli({"export", "s.json", "--joints=j.csv", "--frames", "12"});
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(*n.value().frame_range, (std::pair<uint32_t, uint32_t>{0, 12}));
    EXPECT_TRUE(n.value().character_ranges.empty());
}

TEST(Cli, ExportRefusesBadSelectionsNamingThem) {
    auto expect_error = [](std::vector<std::string> args, const std::string& part) {
        auto o = parse_cli(args);
        ASSERT_FALSE(o.ok());
        EXPECT_NE(o.error().to_string().find(part), std::string::npos) << o.error().to_string();
    };
    expect_error({"export", "s.json"}, "needs --joints");
    expect_error({"export", "s.json", "--joints", "j.csv", "--frames", "9:3"}, "'--frames' expects A:B");
    expect_error({"export", "s.json", "--joints", "j.csv", "--frames", "a:b"}, "'a:b'");
    expect_error({"export", "s.json", "--joints", "j.csv", "--characters", "4-2"}, "bad item '4-2'");
    expect_error({"export", "s.json", "--joints", "j.csv", "--characters", "1,,2"}, "bad item ''");
    expect_error({"export", "s.json", "--joints", "j.csv", "--colour", "level"}, "not known to 'aloha export'");
    expect_error({"render", "s.json", "--motion-metrics"}, "not known to 'aloha render'");
}

TEST(ExportSkin, CommandLineTakesFrameCharacterLevelAndGlb) {
    auto o = parse_cli({"export", "s.json", "--frame", "12", "--character", "3", "--level", "1", "--out", "x.glb"});
    ASSERT_TRUE(o.ok()) << o.error().to_string();
    EXPECT_EQ(o.value().out, "x.glb");
    EXPECT_EQ(o.value().frame, 12u);
    EXPECT_EQ(o.value().character, 3u);
    EXPECT_EQ(o.value().level, 1u);
    auto no_level = parse_cli({"export", "s.json", "--frame=0", "--character=0", "--out=Y.GLB", "--force"});
    ASSERT_TRUE(no_level.ok()) << no_level.error().to_string();
    EXPECT_FALSE(no_level.value().level);
    EXPECT_TRUE(no_level.value().force);
    auto expect_error = [](std::vector<std::string> args, const std::string& part) {
        auto r = parse_cli(args);
        ASSERT_FALSE(r.ok());
        EXPECT_NE(r.error().to_string().find(part), std::string::npos) << r.error().to_string();
    };
    expect_error({"export", "s.json", "--character", "0", "--out", "x.glb"}, "needs --frame N");
    expect_error({"export", "s.json", "--frame", "0", "--out", "x.glb"}, "needs --character I");
    expect_error({"export", "s.json", "--frame", "0", "--character", "0", "--out", "x.gltf"}, "expects a .glb file");
    expect_error({"export", "s.json", "--frame", "0", "--character", "0", "--out", "x.glb", "--joints", "j.csv"}, "not both");
    expect_error({"export", "s.json", "--joints", "j.csv", "--frame", "3"}, "go with --out FILE.glb");
    expect_error({"export", "s.json", "--frame", "0", "--character", "0", "--out", "x.glb", "--characters", "1"}, "go with --joints");
    expect_error({"export", "s.json", "--frame", "-1", "--character", "0", "--out", "x.glb"}, "'--frame'");
    expect_error({"export", "s.json", "--frame", "0", "--character", "x", "--out", "x.glb"}, "'--character' expects a whole number");
    expect_error({"export", "s.json", "--frame", "0", "--character", "0", "--level", "300", "--out", "x.glb"}, "'--level'");
}

TEST(Cli, ProfileTakesMotionMetrics) {
    auto o = parse_cli({"profile", "s.json", "--motion-metrics"});
    ASSERT_TRUE(o.ok());
    EXPECT_TRUE(o.value().motion_metrics);
}

}  // namespace
}  // namespace aloha::tool
