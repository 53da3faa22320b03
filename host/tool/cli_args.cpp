// The aloha command line on CLI11: one CLI::App with a subcommand per command, each declaring the options
// it accepts with their checks (cli_checks.hpp). CLI11's exceptions stop at parse_cli, which returns them as
// Error values naming the argument; nothing here runs per frame.
#include "host/tool/cli_args.hpp"

#include "engine/core/blob_store.hpp"
#include "host/tool/cli_checks.hpp"
#include "systems/render/far_layer.hpp"

#include <CLI/CLI.hpp>

#include <cctype>
#include <memory>
#include <set>

namespace aloha::tool {

namespace {

const std::set<std::string> kCommands = {"render", "view", "profile", "scale", "export", "validate"};

// What the subcommands write into: CliOptions plus the text of options converted after the parse.
struct Bindings {
    CliOptions o;
    std::string lod = "on", cache = "on", budget, occlusion = "on", gpu_overlap = "auto", cache_max_mb, counts, characters, frames, frame_range, selection;
    std::string warmup, frame, width, height, threads, seed, compare_frames, character, level, far_layer, far_layer_meshes,
        distant_layer, texture_mips, texture_max, impostor_elevations, impostor_views, far_layer_alpha, impostor_share;
    std::string budget_ms, budget_single_ms, budget_animation_ms, budget_geometry_ms;
};

// Options every simulating command shares (not `validate`); `export` has no viewport or overlay and
// reads --characters as a selection, not a crowd size.
void add_common(CLI::App& c, Bindings& b, bool is_export) {
    c.add_option("--threads", b.threads, "worker threads (0 = all cores)")->check(whole_number(0, 256));
    c.add_option("--seed", b.seed, "override every crowd's seed")->check(whole_number_u64());
    c.add_option("--lod", b.lod, "LOD on (rules) or off (every character at the top level)")->check(on_off());
    c.add_option("--cache", b.cache,
                 "reuse the character types' load-time bakes from the bake cache and save new ones (default on)")->check(on_off());
    c.add_option("--cache-dir", b.o.cache_dir,
                 "the bake cache's directory (default: $ALOHA_CACHE_DIR, else $XDG_CACHE_HOME/aloha, else ~/.cache/aloha)")
        ->check(non_empty());
    c.add_option("--cache-max-mb", b.cache_max_mb,
                 "the bake cache's size limit in MiB, the entries used longest ago removed first (0 = no limit; default: "
                 "$ALOHA_CACHE_MAX_MB, else 1024)")
        ->check(whole_number(0, 4'000'000'000));
    c.add_option("--budget-ms", b.budget_ms,
                 "CPU frame budget: lower detail where least noticed to fit X ms (the rule file's animation/geometry "
                 "split kept, scaled to X; without a split one total)")->check(milliseconds());
    c.add_option("--budget-animation-ms", b.budget_animation_ms, "the motion system's budget (overrides the rule file's)")
        ->check(milliseconds());
    c.add_option("--budget-geometry-ms", b.budget_geometry_ms,
                 "the muscle + spring_skin systems' budget (overrides the rule file's)")->check(milliseconds());
    c.add_option("--budget-single-ms", b.budget_single_ms,
                 "one total for the CPU systems, geometry and animation demoted together (the single-total "
                 "controller), whatever the rule file's budget says")->check(milliseconds());
    c.add_option("--budget", b.budget, "run the rule file's budget or not (default: as the file says)")->check(on_off());
    c.add_option("--tier", b.o.tier, "hardware tier of the rules (default: the rule file's default_tier, or auto)")
        ->check(non_empty());
    c.add_option("--occlusion", b.occlusion, "estimate which characters the crowd hides (default on)")->check(on_off());
    c.add_option("--device", b.o.device, "lavapipe | gpu | device index (default: a real GPU if present, else lavapipe)")
        ->check(non_empty());
    c.add_flag("--validation", b.o.validation, "enable Vulkan validation layers");
    if (is_export) return;
    c.add_option("--characters", b.characters, "rescale the scene's crowds to N characters in all")
        ->check(whole_number(1, 1'000'000));
    c.add_option("--width", b.width, "override the viewport width")->check(whole_number(16, 8192));
    c.add_option("--far-layer", b.far_layer,
                 "impostors under PX pixels tall are drawn at half resolution and composited "
                 "with its depth (PX at a 720-pixel viewport height, scaled with it; default " + std::to_string(int(kDefaultFarLayerBelowPx)) + " on a software rasteriser, 0 on a GPU; 0: all at full resolution)")
        ->check(whole_number(0, 8192));
    c.add_option("--far-layer-meshes", b.far_layer_meshes,
                 "characters' meshes under PX pixels tall at 720 lines (not cross-fading) go to the same half-resolution layer (default " +
                     std::to_string(int(kDefaultFarLayerMeshesBelowPx)) + " on a software rasteriser, 0 on a GPU; 0: all at full resolution)")
        ->check(whole_number(0, 8192));
    c.add_option("--far-layer-alpha", b.far_layer_alpha,
                 "the far and distant layers' alpha test in percent of coverage (default " +
                     std::to_string(int(kDefaultFarLayerAlphaTest * 100.0f + 0.5f)) +
                     ": at half resolution a test at 50 loses limbs under a layer texel wide; full resolution tests at 50)")
        ->check(whole_number(1, 100));
    c.add_option("--distant-layer", b.distant_layer,
                 "far impostors under PX pixels tall at 720 lines are drawn at a quarter of the resolution instead of half "
                 "(default 0: none; faster on a software rasteriser, coarser far crowd)")
        ->check(whole_number(0, 8192));
    c.add_option("--impostor-elevations", b.impostor_elevations,
                 "bands of views in each impostor atlas: 1 level views only, N evenly from level to straight down "
                 "(default 3: 0, 45 and 90 degrees; each band costs one level atlas's memory and bake time)")
        ->check(whole_number(1, 8));
    c.add_option("--impostor-share", b.impostor_share,
                 "body variants whose surfaces lie within PX pixels of an atlas already baked, scaled, draw that atlas "
                 "instead of baking their own (default 1; 0: every variant bakes its own)")
        ->check(atlas_pixels());
    c.add_option("--impostor-views", b.impostor_views,
                 "impostors drawn at full resolution show their two nearest views, walk phases and bands of elevation blended "
                 "(blend: up to four atlas reads a fragment) or one of them a pixel by a dither of their weights (pick: one "
                 "read), fading in from the far layer's limit to twice it, or the nearest (nearest); default nearest on a "
                 "software rasteriser, blend on a GPU; the far layers show the nearest")
        ->check(one_of({impostor_views_name(ImpostorViews::Blend), impostor_views_name(ImpostorViews::Pick),
                        impostor_views_name(ImpostorViews::Nearest)}));
    c.add_option("--texture-mips", b.texture_mips,
                 "material textures read from the two nearest mip levels blended (blend, trilinear) or from the nearest one "
                 "(nearest; default nearest on a software rasteriser, blend on a GPU)")
        ->check(one_of({"blend", "nearest"}));
    c.add_option("--texture-max", b.texture_max,
                 "material textures wider or taller than PX are halved at load until they fit (default 2048; 0: no limit)")
        ->check(whole_number(0, 16384));
    c.add_option("--height", b.height, "override the viewport height")->check(whole_number(16, 8192));
    c.add_option("--overlay", b.o.overlay, "draw bones, muscles and/or springs over the characters (e.g. bones,springs)")
        ->check(member_list({"bones", "muscles", "springs"}));
}

void add_colour(CLI::App& c, Bindings& b) {
    c.add_option("--colour", b.o.colour, "shaded | level | rule | method")
        ->check(one_of({"shaded", "level", "rule", "method"}));
}

void add_frames(CLI::App& c, Bindings& b, const std::string& what) {
    c.add_option("--frames", b.frames, what)->check(whole_number(1, 10'000'000));
}

// The whole command line; `b` receives the values.
std::unique_ptr<CLI::App> make_app(Bindings& b) {
    auto app = std::make_unique<CLI::App>("aloha: adaptive level of detail for crowds of layered virtual humans", "aloha");
    app->require_subcommand(0, 1);
    auto command = [&](const std::string& name, const std::string& synopsis, const std::string& about) {
        CLI::App* c = app->add_subcommand(name, synopsis + "\n  " + about);
        c->add_option("scene", b.o.scene, "scene file");
        return c;
    };
    CLI::App* render = command("render", "aloha render SCENE --frame N --out frame.png [options]",
                               "Simulates frames 0..N headless and writes frame N as PNG.");
    render->add_option("--frame", b.frame, "frame to write (default: the last)")->check(whole_number(0, 10'000'000));
    render->add_option("--out", b.o.out, "PNG path (default frame.png; refuses to overwrite without --force)")->check(non_empty());
    render->add_flag("--force", b.o.force, "allow overwriting the output");
    add_colour(*render, b);
    add_common(*render, b, false);

    CLI::App* view = command("view", "aloha view SCENE [options]",
                             "Opens a window (GLFW) with orbit/fly camera and an overlay of timings, the LOD histogram "
                             "and live rules.");
    add_frames(*view, b, "close after N frames (for tests)");
    view->add_option("--out", b.o.out, "save the last frame as PNG")->check(non_empty());
    add_colour(*view, b);
    add_common(*view, b, false);

    CLI::App* profile = command("profile", "aloha profile SCENE [--frames N] [--warmup W] [--out DIR] [options]",
                                "Runs headless and writes report.json, frames.csv, trace.json (Perfetto), "
                                "frame_times.svg, last_frame.png.");
    add_frames(*profile, b, "measured frames (default: the scene's)");
    profile->add_option("--warmup", b.warmup, "frames run before measuring (default 30)")->check(whole_number(0, 1'000'000));
    profile->add_option("--out", b.o.out, "output folder (default out/profile; existing reports are kept unless --force)")
        ->check(non_empty());
    profile->add_flag("--force", b.o.force, "allow overwriting existing reports");
    profile->add_flag("--fidelity", b.o.fidelity,
                      "also render each frame at full detail and report screen-space deviation, PSNR, popping");
    profile->add_flag("--no-render", b.o.no_render, "CPU systems only (refined skins are computed each frame, not kept)");
    profile->add_flag("--quiet", b.o.quiet, "no progress bar");
    profile->add_flag("--compare-lod", b.o.compare_lod, "also run the scene with LOD off (CPU systems) and report the slowdown ratio");
    profile->add_option("--compare-frames", b.compare_frames, "frames of that LOD-off run (default 10)")
        ->check(whole_number(1, 100'000));
    profile->add_flag("--motion-metrics", b.o.motion_metrics,
                      "foot skate and pops per animation level and update interval (report.json and the printed "
                      "table; see docs/MOTION.md for the contact thresholds)");
    profile->add_flag("--gpu-passes", b.o.gpu_passes,
                      "GPU timestamps after every pass (each level's meshes, proxies, lines, resolve) in report.json, "
                      "trace.json and the table; on lavapipe each flushes and a pass's figure can hold earlier passes' "
                      "rasterisation: compare frame totals there (docs/PERFORMANCE.md)");
    profile->add_flag("--constant-fragments", b.o.constant_fragments,
                      "meshes and proxies drawn unlit with a constant-colour fragment shader, to tell the fragment "
                      "cost from the vertex and binning cost (profiling only)");
    profile->add_option("--gpu-overlap", b.gpu_overlap,
                        "on: the GPU draws a frame while the next frame's CPU systems run (two frames in flight; the "
                        "whole frame is the interval between frames); off: each frame waits for its GPU work; auto (default): "
                        "overlapped while the GPU's frame is longer than 16.7 ms and the CPU systems take 1 ms or more "
                        "(docs/PERFORMANCE.md); with --fidelity every frame is waited for")
        ->check(one_of({"on", "off", "auto"}));
    add_colour(*profile, b);
    add_common(*profile, b, false);

    CLI::App* scale = command("scale", "aloha scale SCENE --counts 1000,2000,5000,10000,20000 [--frames N] [--warmup W] [--out DIR]",
                              "Rescales the scene's crowds to each count, profiles the CPU systems (and the render "
                              "unless --no-render) and writes scaling.json, scaling.csv and scaling.svg.");
    scale->add_option("--counts", b.counts, "crowd sizes, comma-separated whole numbers in [1, 1000000]")
        ->check(count_list());
    add_frames(*scale, b, "measured frames per count (default: the scene's)");
    scale->add_option("--warmup", b.warmup, "frames run before measuring (default 30)")->check(whole_number(0, 1'000'000));
    scale->add_option("--out", b.o.out, "output folder")->check(non_empty());
    scale->add_flag("--force", b.o.force, "allow overwriting existing reports");
    scale->add_flag("--quiet", b.o.quiet, "no progress bar");
    scale->add_flag("--no-render", b.o.no_render, "CPU systems only");
    add_common(*scale, b, false);

    CLI::App* exp = command("export",
                            "aloha export SCENE --joints FILE.csv [--characters LIST] [--frames A:B] [options]\n"
                            "  aloha export SCENE --frame N --character I [--level L] --out FILE.glb [options]",
                            "Runs the scene headless (no rendering) and writes every joint's world position per "
                            "frame, with each character's animation level, update interval, method and whether a "
                            "transition is under way (--joints); or one character's displayed skin and skeleton at "
                            "frame N, in world space, as glTF 2.0 binary (--out).");
    exp->add_option("--joints", b.o.joints, "CSV path (refuses to overwrite without --force)")->check(non_empty());
    exp->add_option("--characters", b.selection, "spawn indices and inclusive ranges, e.g. 0,5,10-20 (default: every character)")
        ->check(index_ranges());
    exp->add_option("--frames", b.frame_range,
                    "frames A to B-1, 0 = the first frame run (default: 0 to the scene's frames); a single N means 0:N")
        ->check(frame_range());
    exp->add_option("--out", b.o.out, "glTF binary path (.glb; refuses to overwrite without --force)")->check(non_empty());
    exp->add_option("--frame", b.frame, "with --out: the frame whose skin is written (0 = the first frame run)")
        ->check(whole_number(0, 10'000'000));
    exp->add_option("--character", b.character, "with --out: the character (spawn index, as --characters counts)")
        ->check(whole_number(0, 10'000'000));
    exp->add_option("--level", b.level,
                    "with --out: hold the character at this geometric level from the first frame (default: the "
                    "level the rules give it)")->check(whole_number(0, 254));
    exp->add_flag("--force", b.o.force, "allow overwriting the output");
    add_common(*exp, b, true);

    command("validate", "aloha validate SCENE | CHARACTER_FILE",
            "Checks the scene, its rule file and every asset it names; exits 1 and prints every problem found. Given a "
            "character file (.glb, .gltf, .vrm, .bvh), loads it alone and prints what ALOHA makes of it (mapping, units, "
            "levels, notes).");
    return app;
}

// Converts what the checks already accepted into CliOptions.
void convert(Bindings& b) {
    CliOptions& o = b.o;
    auto u32 = [](const std::string& s) { return static_cast<uint32_t>(std::stoul(s)); };
    auto ms = [](const std::string& s, std::optional<double>& out) { if (!s.empty()) out = std::stod(s); };
    o.lod = b.lod == "on";
    o.cache = b.cache == "on";
    o.occlusion = b.occlusion == "on";
    o.gpu_overlap = parse_gpu_overlap(b.gpu_overlap).value_or(GpuOverlap::Auto);  // checked by one_of above
    if (!b.budget.empty()) o.budget = b.budget == "on";
    ms(b.budget_ms, o.budget_ms);
    ms(b.budget_single_ms, o.budget_single_ms);
    ms(b.budget_animation_ms, o.budget_animation_ms);
    ms(b.budget_geometry_ms, o.budget_geometry_ms);
    if (!b.frames.empty()) o.frames = u32(b.frames);
    if (!b.warmup.empty()) o.warmup = u32(b.warmup);
    if (!b.frame.empty()) o.frame = u32(b.frame);
    if (!b.width.empty()) o.width = u32(b.width);
    if (!b.far_layer.empty()) o.far_layer_px = float(u32(b.far_layer));
    if (!b.far_layer_meshes.empty()) o.far_layer_meshes_px = float(u32(b.far_layer_meshes));
    if (!b.distant_layer.empty()) o.distant_layer_px = float(u32(b.distant_layer));
    if (!b.impostor_elevations.empty()) o.impostor_elevations = u32(b.impostor_elevations);
    if (!b.impostor_share.empty()) o.impostor_share_px = std::stof(b.impostor_share);
    if (!b.texture_mips.empty()) o.blend_texture_mips = b.texture_mips == "blend";
    for (const ImpostorViews views : {ImpostorViews::Nearest, ImpostorViews::Blend, ImpostorViews::Pick})
        if (b.impostor_views == impostor_views_name(views)) o.impostor_views = views;  // one_of() checked the word
    if (!b.far_layer_alpha.empty()) o.far_layer_alpha_test = float(u32(b.far_layer_alpha)) / 100.0f;
    if (!b.texture_max.empty()) o.max_texture_side = u32(b.texture_max);
    if (!b.height.empty()) o.height = u32(b.height);
    if (!b.threads.empty()) o.threads = u32(b.threads);
    if (!b.cache_max_mb.empty()) o.cache_max_bytes = parse_cache_limit_mib(b.cache_max_mb);
    if (!b.compare_frames.empty()) o.compare_frames = u32(b.compare_frames);
    if (!b.characters.empty()) o.characters = u32(b.characters);
    if (!b.character.empty()) o.character = u32(b.character);
    if (!b.level.empty()) o.level = u32(b.level);
    if (!b.seed.empty()) o.seed = std::stoull(b.seed);
    if (!b.counts.empty()) o.counts = parse_count_list(b.counts);
    if (!b.selection.empty()) o.character_ranges = parse_index_ranges(b.selection);
    if (!b.frame_range.empty()) o.frame_range = parse_frame_range(b.frame_range);
}

// CLI11's "not expected" list as our message: the first stray option, else the stray argument.
Error extras_error(const CLI::App& command, const std::string& scene) {
    const std::vector<std::string> extras = command.remaining();
    for (const std::string& e : extras)
        if (e.rfind("-", 0) == 0)
            return cli_error("option '" + e.substr(0, e.find('=')) + "' is not known to 'aloha " + command.get_name() + "'");
    const std::string first = extras.empty() ? std::string() : extras.front();
    return cli_error("unexpected argument '" + first + "' (the scene is already '" + scene + "')");
}

// CLI11's "NAME: problem" as "option 'NAME' problem"; a missing value as "option 'NAME' needs a value".
Error parse_error(const CLI::ParseError& e) {
    const std::string what = e.what();
    const size_t colon = what.find(": ");
    if (what.rfind("--", 0) != 0 || colon == std::string::npos) return cli_error(what);
    const std::string name = what.substr(0, colon);
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) return cli_error("option '" + name + "' needs a value");
    return cli_error("option '" + name + "' " + what.substr(colon + 2));
}

// `aloha export` writes joints (--joints) or one skin (--out FILE.glb), each with its own options.
Status check_export(const CliOptions& o) {
    if (o.joints.empty() == o.out.empty())
        return cli_error("'aloha export' needs --joints FILE.csv (joint positions) or --out FILE.glb (one character's skin, "
                         "with --frame and --character), not both");
    if (!o.joints.empty()) {
        if (o.frame || o.character || o.level)
            return cli_error("--frame, --character and --level go with --out FILE.glb, not --joints (use --frames and --characters)");
        return {};
    }
    if (!o.character_ranges.empty() || o.frame_range)
        return cli_error("--characters and --frames go with --joints; --out FILE.glb takes one --character and one --frame");
    if (!o.frame) return cli_error("'aloha export --out' needs --frame N (the frame whose skin is written)");
    if (!o.character) return cli_error("'aloha export --out' needs --character I (the character whose skin is written)");
    const size_t dot = o.out.rfind('.');
    std::string ext = dot == std::string::npos ? std::string() : o.out.substr(dot);
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".glb") return cli_error("option '--out' expects a .glb file (glTF 2.0 binary), got '" + o.out + "'");
    return {};
}

}  // namespace

Result<CliOptions> parse_cli(const std::vector<std::string>& args) {
    CliOptions help;
    help.command = "help";
    if (args.empty() || args[0] == "--help" || args[0] == "-h") return help;
    if (args[0] == "help") {
        if (args.size() > 2) return cli_error("unexpected argument '" + args[2] + "' ('aloha help' takes one command)");
        if (args.size() == 2) help.scene = args[1];
        return help;
    }
    if (!kCommands.count(args[0]))
        return cli_error("unknown command '" + args[0] + "' (expected render, view, profile, scale, export or validate; try --help)");
    Bindings b;
    b.o.command = args[0];
    auto app = make_app(b);
    CLI::App* command = app->get_subcommand(args[0]);
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 consumes from the back
    try {
        app->parse(reversed);
    } catch (const CLI::CallForHelp&) {
        b.o.help = true;
        return b.o;
    } catch (const CLI::ExtrasError&) {
        return extras_error(*command, b.o.scene);
    } catch (const CLI::ParseError& e) {
        return parse_error(e);
    }
    convert(b);
    const CliOptions& o = b.o;
    if (o.scene.empty()) return cli_error("'aloha " + o.command + "' needs a scene file");
    if (!o.cache && !o.cache_dir.empty()) return cli_error("--cache-dir names the bake cache's directory: it goes with --cache on, not off");
    if (!o.cache && o.cache_max_bytes) return cli_error("--cache-max-mb limits the bake cache: it goes with --cache on, not off");
    if (o.command == "scale" && o.counts.empty()) return cli_error("'aloha scale' needs --counts A,B,...");
    if (o.fidelity && b.gpu_overlap == "on")
        return cli_error("--fidelity reads each frame back before the next one starts: it cannot go with --gpu-overlap on");
    if (o.command == "export") {
        if (Status st = check_export(o); !st.ok()) return st.error();
    }
    return b.o;
}

std::string help_text(const std::string& command) {
    Bindings b;
    auto app = make_app(b);
    if (kCommands.count(command)) return app->get_subcommand(command)->help();
    app->footer("'aloha COMMAND --help' describes a command's options.");
    return app->help();
}

}  // namespace aloha::tool
