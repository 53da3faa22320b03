#include "engine/tool/cli_args.hpp"

#include <charconv>
#include <set>

namespace aloha::tool {

namespace {

Error arg_error(const std::string& message) { return make_error("command line", message); }

template <class T>
bool parse_number(const std::string& text, T& out) {
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, out);
    return ec == std::errc() && p == end;
}

const std::set<std::string> kCommands = {"render", "view", "profile", "scale", "export", "validate", "help"};

// Which options each command accepts.
bool accepts(const std::string& command, const std::string& option) {
    static const std::set<std::string> common = {"--help", "-h", "--threads", "--seed", "--lod", "--budget-ms",
                                                 "--characters", "--device", "--validation", "--width", "--height",
                                                 "--overlay", "--budget-animation-ms", "--budget-geometry-ms", "--budget-single-ms",
                                                 "--budget", "--tier", "--occlusion"};
    if (command == "export")  // --characters selects characters here, it does not rescale the crowd
        return option == "--joints" || option == "--characters" || option == "--frames" || option == "--force" ||
               (common.count(option) && option != "--overlay" && option != "--width" && option != "--height");
    if (common.count(option)) return command != "validate" || option == "--help" || option == "-h";
    if (command == "render") return option == "--frame" || option == "--out" || option == "--colour" || option == "--force";
    if (command == "view") return option == "--frames" || option == "--colour" || option == "--out";
    if (command == "profile")
        return option == "--frames" || option == "--warmup" || option == "--out" || option == "--fidelity" ||
               option == "--no-render" || option == "--colour" || option == "--force" || option == "--quiet" ||
               option == "--compare-lod" || option == "--compare-frames" || option == "--motion-metrics" ||
               option == "--gpu-passes" || option == "--constant-fragments";
    if (command == "scale")
        return option == "--counts" || option == "--frames" || option == "--warmup" || option == "--out" ||
               option == "--force" || option == "--quiet" || option == "--no-render";
    return false;
}

// export's --joints FILE, --characters LIST (indices and inclusive ranges) and --frames A:B.
Status parse_export_option(const std::string& option, const std::string& value, CliOptions& o) {
    if (value.empty()) return arg_error("option '" + option + "' needs a non-empty value");
    if (option == "--joints") {
        o.joints = value;
        return {};
    }
    if (option == "--frames") {
        const size_t colon = value.find(':');
        uint32_t a = 0, b = 0;
        const bool ok = colon == std::string::npos ? parse_number(value, b)
                                                   : parse_number(value.substr(0, colon), a) && parse_number(value.substr(colon + 1), b);
        if (!ok || b <= a || b > 10'000'000)
            return arg_error("--frames expects A:B with 0 <= A < B <= 10000000 (frames A to B-1) or a frame count N, got '" + value + "'");
        o.frame_range = std::pair{a, b};
        return {};
    }
    o.character_ranges.clear();
    size_t start = 0;
    while (start <= value.size()) {
        const size_t comma = std::min(value.find(',', start), value.size());
        const std::string item = value.substr(start, comma - start);
        const size_t dash = item.find('-');
        uint32_t lo = 0, hi = 0;
        const bool ok = dash == std::string::npos ? parse_number(item, lo) && (hi = lo, true)
                                                  : parse_number(item.substr(0, dash), lo) && parse_number(item.substr(dash + 1), hi);
        if (!ok || hi < lo)
            return arg_error("--characters expects a comma list of character indices and ranges (e.g. 0,5,10-20), got '" +
                             value + "' (bad item '" + item + "')");
        o.character_ranges.emplace_back(lo, hi);
        start = comma + 1;
    }
    return {};
}

}  // namespace

Result<CliOptions> parse_cli(const std::vector<std::string>& args) {
    CliOptions o;
    if (args.empty()) {
        o.command = "help";
        return o;
    }
    o.command = args[0];
    if (o.command == "--help" || o.command == "-h") {
        o.command = "help";
        return o;
    }
    if (!kCommands.count(o.command))
        return arg_error("unknown command '" + o.command + "' (expected render, view, profile, scale, export or validate; try --help)");
    for (size_t i = 1; i < args.size(); ++i) {
        std::string a = args[i];
        std::string value;
        bool has_inline = false;
        if (a.rfind("--", 0) == 0) {
            if (auto eq = a.find('='); eq != std::string::npos) {
                value = a.substr(eq + 1);
                a = a.substr(0, eq);
                has_inline = true;
            }
        } else if (a != "-h") {
            if (!o.scene.empty() || o.command == "help")
                return arg_error("unexpected argument '" + a + "' (the scene is already '" + o.scene + "')");
            o.scene = a;
            continue;
        }
        if (o.command == "help") {
            o.scene = a;
            continue;
        }
        if (!accepts(o.command, a)) return arg_error("option '" + a + "' is not known to 'aloha " + o.command + "'");
        auto take = [&]() -> Result<std::string> {
            if (has_inline) return value;
            if (i + 1 >= args.size()) return arg_error("option '" + a + "' needs a value");
            return args[++i];
        };
        auto take_u32 = [&](uint32_t lo, uint32_t hi) -> Result<uint32_t> {
            auto v = take();
            if (!v.ok()) return v.error();
            uint32_t n = 0;
            if (!parse_number(v.value(), n) || n < lo || n > hi)
                return arg_error("option '" + a + "' expects a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + v.value() + "'");
            return n;
        };
        if (a == "--help" || a == "-h") { o.help = true; continue; }
        if (a == "--fidelity") { o.fidelity = true; continue; }
        if (a == "--no-render") { o.no_render = true; continue; }
        if (a == "--force") { o.force = true; continue; }
        if (a == "--validation") { o.validation = true; continue; }
        if (a == "--quiet") { o.quiet = true; continue; }
        if (a == "--compare-lod") { o.compare_lod = true; continue; }
        if (a == "--motion-metrics") { o.motion_metrics = true; continue; }
        if (a == "--gpu-passes") { o.gpu_passes = true; continue; }
        if (a == "--constant-fragments") { o.constant_fragments = true; continue; }
        if (o.command == "export" && (a == "--joints" || a == "--characters" || a == "--frames")) {
            auto v = take();
            if (!v.ok()) return v.error();
            if (Status st = parse_export_option(a, v.value(), o); !st.ok()) return st.error();
            continue;
        }
        if (a == "--counts") {
            auto v = take();
            if (!v.ok()) return v.error();
            o.counts.clear();
            size_t start = 0;
            const std::string& list = v.value();
            while (start <= list.size()) {
                const size_t comma = std::min(list.find(',', start), list.size());
                uint32_t count = 0;
                if (!parse_number(list.substr(start, comma - start), count) || count < 1 || count > 1'000'000)
                    return arg_error("--counts expects comma-separated whole numbers in [1, 1000000], got '" + list + "'");
                o.counts.push_back(count);
                start = comma + 1;
            }
            continue;
        }
        if (a == "--overlay") {
            auto v = take();
            if (!v.ok()) return v.error();
            size_t start = 0;
            const std::string& list = v.value();
            while (start <= list.size()) {
                const size_t comma = std::min(list.find(',', start), list.size());
                const std::string item = list.substr(start, comma - start);
                if (item != "bones" && item != "muscles" && item != "springs")
                    return arg_error("--overlay expects a comma list of bones, muscles, springs, got '" + list + "'");
                start = comma + 1;
            }
            o.overlay = list;
            continue;
        }
        if (a == "--out" || a == "--colour" || a == "--device" || a == "--lod" || a == "--budget" || a == "--tier" ||
            a == "--occlusion") {
            auto v = take();
            if (!v.ok()) return v.error();
            if (v.value().empty()) return arg_error("option '" + a + "' needs a non-empty value");
            if (a == "--out") o.out = v.value();
            if (a == "--device") o.device = v.value();
            if (a == "--colour") {
                if (v.value() != "shaded" && v.value() != "level" && v.value() != "rule" && v.value() != "method")
                    return arg_error("--colour expects shaded, level, rule or method, got '" + v.value() + "'");
                o.colour = v.value();
            }
            if (a == "--lod" || a == "--budget" || a == "--occlusion") {
                if (v.value() != "on" && v.value() != "off")
                    return arg_error(a + " expects on or off, got '" + v.value() + "'");
                if (a == "--lod") o.lod = v.value() == "on";
                if (a == "--budget") o.budget = v.value() == "on";
                if (a == "--occlusion") o.occlusion = v.value() == "on";
            }
            if (a == "--tier") o.tier = v.value();
            continue;
        }
        if (a == "--budget-ms" || a == "--budget-animation-ms" || a == "--budget-geometry-ms" || a == "--budget-single-ms") {
            auto v = take();
            if (!v.ok()) return v.error();
            double d = 0;
            if (!parse_number(v.value(), d) || !(d > 0.0 && d < 10000.0))
                return arg_error(a + " expects a number of milliseconds in (0, 10000), got '" + v.value() + "'");
            (a == "--budget-ms"             ? o.budget_ms
             : a == "--budget-animation-ms" ? o.budget_animation_ms
             : a == "--budget-single-ms"    ? o.budget_single_ms
                                            : o.budget_geometry_ms) = d;
            continue;
        }
        if (a == "--seed") {
            auto v = take();
            if (!v.ok()) return v.error();
            uint64_t s = 0;
            if (!parse_number(v.value(), s)) return arg_error("--seed expects a whole number, got '" + v.value() + "'");
            o.seed = s;
            continue;
        }
        Result<uint32_t> n = arg_error("");
        if (a == "--frames") n = take_u32(1, 10'000'000), o.frames = n.ok() ? std::optional<uint32_t>(n.value()) : std::nullopt;
        else if (a == "--warmup") n = take_u32(0, 1'000'000), o.warmup = n.ok() ? n.value() : 0;
        else if (a == "--frame") n = take_u32(0, 10'000'000), o.frame = n.ok() ? std::optional<uint32_t>(n.value()) : std::nullopt;
        else if (a == "--width") n = take_u32(16, 8192), o.width = n.ok() ? std::optional<uint32_t>(n.value()) : std::nullopt;
        else if (a == "--height") n = take_u32(16, 8192), o.height = n.ok() ? std::optional<uint32_t>(n.value()) : std::nullopt;
        else if (a == "--threads") n = take_u32(0, 256), o.threads = n.ok() ? n.value() : 0;
        else if (a == "--compare-frames") n = take_u32(1, 100000), o.compare_frames = n.ok() ? n.value() : 0;
        else if (a == "--characters") n = take_u32(1, 1'000'000), o.characters = n.ok() ? std::optional<uint32_t>(n.value()) : std::nullopt;
        if (!n.ok()) return n.error();
    }
    if (o.command != "help" && !o.help && o.scene.empty()) return arg_error("'aloha " + o.command + "' needs a scene file");
    if (o.command == "scale" && !o.help && o.counts.empty()) return arg_error("'aloha scale' needs --counts A,B,...");
    if (o.command == "export" && !o.help && o.joints.empty()) return arg_error("'aloha export' needs --joints FILE.csv");
    return o;
}

std::string help_text(const std::string& command) {
    const std::string common =
        "  --threads T        worker threads (0 = all cores)\n"
        "  --seed S           override every crowd's seed\n"
        "  --lod on|off       LOD on (rules) or off (every character at the top level)\n"
        "  --budget-ms X      CPU frame budget: lower detail where least noticed to fit X ms (the rule file's\n"
        "                     animation/geometry split kept, scaled to X; without a split one total)\n"
        "  --budget-animation-ms X, --budget-geometry-ms X  separate budgets of the motion system and of the\n"
        "                     muscle + spring_skin systems (override the rule file's)\n"
        "  --budget-single-ms X  one total for the CPU systems, geometry and animation demoted together (the\n"
        "                     single-total controller), whatever the rule file's budget says\n"
        "  --budget on|off    run the rule file's budget or not (default: as the file says)\n"
        "  --tier NAME        hardware tier of the rules (default: the rule file's default_tier, or auto)\n"
        "  --occlusion on|off estimate which characters the crowd hides (attribute 'occluded'; default on)\n"
        "  --characters N     rescale the scene's crowds to N characters in all\n"
        "  --width W, --height H  override the viewport\n"
        "  --device D         lavapipe | gpu | device index (default: a real GPU if present, else lavapipe)\n"
        "  --validation       enable Vulkan validation layers\n"
        "  --overlay LIST     draw bones, muscles and/or springs over the characters (e.g. bones,springs)\n";
    if (command == "render")
        return "aloha render SCENE --frame N --out frame.png [options]\n"
               "  Simulates frames 0..N headless and writes frame N as PNG.\n"
               "  --frame N          frame to write (default: the last)\n"
               "  --out FILE         PNG path (default frame.png; refuses to overwrite without --force)\n"
               "  --colour C         shaded | level | rule | method\n" + common;
    if (command == "view")
        return "aloha view SCENE [options]\n"
               "  Opens a window (GLFW) with orbit/fly camera and an overlay of timings, the LOD histogram and live rules.\n"
               "  --frames N         close after N frames (for tests); --out FILE saves the last frame as PNG\n"
               "  --colour C         shaded | level | rule | method\n" + common;
    if (command == "profile")
        return "aloha profile SCENE [--frames N] [--warmup W] [--out DIR] [options]\n"
               "  Runs headless and writes report.json, frames.csv, trace.json (Perfetto), frame_times.svg, last_frame.png.\n"
               "  --frames N         measured frames (default: the scene's)\n"
               "  --warmup W         frames run before measuring (default 30)\n"
               "  --out DIR          output folder (default out/profile; existing reports are kept unless --force)\n"
               "  --fidelity         also render each frame at full detail and report screen-space deviation, PSNR, popping\n"
               "  --no-render        CPU systems only (refined skins are computed each frame, not kept)\n"
               "  --quiet            no progress bar\n"
               "  --compare-lod      also run the scene with LOD off (CPU systems) and report the slowdown ratio\n"
               "  --compare-frames K frames of that LOD-off run (default 10)\n"
               "  --motion-metrics   foot skate and pops per animation level and update interval (report.json and the\n"
               "                     printed table; see docs/MOTION.md for the contact thresholds)\n"
               "  --gpu-passes       GPU timestamps after every pass (each level's meshes, proxies, lines, resolve) in\n"
               "                     report.json, trace.json and the table; on lavapipe each flushes (docs/PERFORMANCE.md)\n"
               "  --constant-fragments  meshes and proxies drawn unlit with a constant-colour fragment shader, to\n"
               "                     tell the fragment cost from the vertex and binning cost (profiling only)\n" + common;
    if (command == "export")
        return "aloha export SCENE --joints FILE.csv [--characters LIST] [--frames A:B] [options]\n"
               "  Runs the scene headless (no rendering) and writes every joint's world position per frame, with each\n"
               "  character's animation level, update interval, method and whether a transition is under way.\n"
               "  --joints FILE      CSV path (refuses to overwrite without --force)\n"
               "  --characters LIST  spawn indices and inclusive ranges, e.g. 0,5,10-20 (default: every character)\n"
               "  --frames A:B       frames A to B-1, 0 = the first frame run (default: 0 to the scene's frames);\n"
               "                     a single N means 0:N\n"
               "  --threads, --seed, --lod, --budget*, --tier, --occlusion, --device, --validation as for profile\n";
    if (command == "scale")
        return "aloha scale SCENE --counts 1000,2000,5000,10000,20000 [--frames N] [--warmup W] [--out DIR]\n"
               "  Rescales the scene's crowds to each count, profiles the CPU systems (and the render unless\n"
               "  --no-render) and writes scaling.json, scaling.csv and scaling.svg: frame time against crowd size.\n" + common;
    if (command == "validate")
        return "aloha validate SCENE\n"
               "  Checks the scene, its rule file and every asset it names; exits 1 and prints every problem found.\n";
    return "aloha: adaptive level of detail for crowds of layered virtual humans\n"
           "usage: aloha COMMAND SCENE [options]\n"
           "commands:\n"
           "  render    render one frame headless to PNG\n"
           "  view      open a window with a live overlay\n"
           "  profile   headless frame-time profile (report, trace, CSV, plot, PNG)\n"
           "  scale     frame time against crowd size\n"
           "  export    joint positions per frame to CSV\n"
           "  validate  check a scene, its rules and assets\n"
           "'aloha COMMAND --help' describes a command's options.\n";
}

}  // namespace aloha::tool
