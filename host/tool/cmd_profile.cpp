// `aloha profile`: runs a scene headless and writes report.json, frames.csv, trace.json (Chrome Trace
// Event format), frame_times.svg and last_frame.png, with a progress bar and a summary table.
#include "engine/scheduler/chrome_trace.hpp"
#include "host/tool/commands.hpp"
#include "host/scene/world_diagnostics.hpp"
#include "host/tool/fidelity.hpp"
#include "host/tool/motion_recorder.hpp"
#include "host/tool/profile_cache.hpp"
#include "host/tool/profile_gpu.hpp"
#include "host/tool/profile_lod.hpp"
#include "host/tool/session.hpp"
#include "host/tool/stats.hpp"
#include "host/tool/switch_hitch.hpp"
#include "systems/lod/rule_table.hpp"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace aloha::tool {

namespace {

struct FrameRecord {
    std::vector<double> system_ms;  // per scheduler system
    double cpu_ms = 0, render_ms = 0, gpu_ms = -1, frame_ms = 0;
    double process_cpu_ms = 0;  // CPU time of every thread of the process (lavapipe's too) during the step
    bool overlapped = false;    // the frame's GPU work was left in flight (GpuOverlapPolicy)
    std::vector<uint32_t> geom_levels, anim_levels;
    std::array<uint32_t, 6> geom_methods{};
    std::array<uint32_t, 3> walk_methods{};
    FidelityFrame fidelity;
    LodSample lod;
    GpuSample gpu;
};

// The header's note on frame pacing: how many measured frames were overlapped, under which mode.
std::string gpu_overlap_line(GpuOverlap mode, size_t overlapped, size_t frames) {
    if (mode == GpuOverlap::Off) return "";
    if (mode == GpuOverlap::On) return ", GPU overlapped with the next frame (--gpu-overlap on)";
    return ", GPU overlapped with the next frame in " + std::to_string(overlapped) + " of " + std::to_string(frames) +
           " frames (--gpu-overlap auto)";
}

void progress(size_t done, size_t total, bool tty, const std::string& label) {
    if (total == 0) return;
    const size_t step = std::max<size_t>(1, total / 10);
    if (!tty && done != total && done % step != 0) return;
    const int width = 30;
    const int filled = static_cast<int>(width * done / total);
    std::cerr << (tty ? "\r" : "") << label << " [" << std::string(static_cast<size_t>(filled), '#')
              << std::string(static_cast<size_t>(width - filled), '.') << "] " << done << "/" << total
              << (tty && done != total ? "" : "\n") << std::flush;
}

// CPU time used so far by every thread of this process (the scheduler's workers and, on a software device,
// lavapipe's queue and rasteriser threads), in ms: a work figure the machine's load inflates far less than wall time.
double process_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

template <class Get>
auto series_of(const std::vector<FrameRecord>& records, Get get) {
    std::vector<std::decay_t<decltype(get(records.front()))>> v;
    for (const auto& r : records) v.push_back(get(r));
    return v;
}

std::string fmt(double v) {
    std::ostringstream o;
    o << std::fixed << std::setprecision(v < 10 ? 3 : 2) << v;
    return o.str();
}

}  // namespace

int run_profile(const CliOptions& options) {
    const std::string out = options.out.empty() ? "out/profile" : options.out;
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(out + "/report.json", ec) && !options.force) {
        print_error(out + "/report.json already exists; pass --force to overwrite the reports in " + out);
        return 1;
    }
    fs::create_directories(out, ec);
    if (ec) {
        print_error("cannot create output folder " + out + ": " + ec.message());
        return 1;
    }
    const bool render = !options.no_render;
    auto opened = open_session(options, render);
    if (!opened.ok()) {
        print_error(opened.error().to_string());
        return 1;
    }
    Session& s = *opened.value();
    World& world = *s.world;
    const RuleTable& table = world.rules().table();
    const Scheduler& sched = world.scheduler();
    const size_t systems = sched.system_count();
    // The Render phase (draw-list gathering, upload, GPU) is reported apart from the CPU systems.
    std::vector<bool> is_render(systems, false);
    for (const auto& pass : sched.plan())
        if (pass.phase == WorldPhase::Render)
            for (uint32_t i : pass.systems) is_render[i] = true;
    const uint32_t frames = s.scene.frames;
    const bool tty = !options.quiet && isatty(2);

    std::unique_ptr<FidelityProbe> fidelity;
    if (options.fidelity) {
        if (!render) {
            print_error("--fidelity needs rendering (drop --no-render)");
            return 1;
        }
        auto probe = FidelityProbe::create(s);
        if (!probe.ok()) {
            print_error(probe.error().to_string());
            return 1;
        }
        fidelity = std::move(probe.value());
    }

    for (uint32_t f = 0; f < options.warmup; ++f) {
        world.step();
        if (!options.quiet) progress(f + 1, options.warmup, tty, "warm-up ");
    }
    const std::vector<GeometryWork> work_before = geometry_work(world);  // the measured frames' work is the difference
    std::vector<TraceEvent> trace;
    world.scheduler().set_trace_sink([&](const TraceEvent& e) { trace.push_back(e); });
    std::vector<FrameRecord> records;
    records.reserve(frames);
    // Motion metrics are recorded between steps: they add to the wall time, not to the frame times.
    std::unique_ptr<MotionRecorder> motion;
    if (options.motion_metrics) motion = std::make_unique<MotionRecorder>(world);
    const auto wall_start = std::chrono::steady_clock::now();
    for (uint32_t f = 0; f < frames; ++f) {
        const float before = world.time();
        const double cpu_before = process_cpu_ms();
        world.step();
        const double cpu_after = process_cpu_ms();
        if (motion) motion->record(world, world.time() - before);
        if (!world.render_status().ok()) {
            print_error(world.render_status().error().to_string());
            return 1;
        }
        FrameRecord r;
        r.system_ms.resize(systems);
        for (uint32_t i = 0; i < systems; ++i) {
            r.system_ms[i] = static_cast<double>(sched.timings(i).latest()) * 1e-6;
            if (is_render[i]) r.render_ms += r.system_ms[i];
            else r.cpu_ms += r.system_ms[i];
        }
        r.frame_ms = static_cast<double>(sched.frame_timings().latest()) * 1e-6;
        r.gpu_ms = world.last_gpu_ms();
        r.process_cpu_ms = cpu_after - cpu_before;
        r.overlapped = world.gpu_overlap().overlapping();
        const LodStats& st = world.lod_stats();
        r.geom_levels = st.per_geom_level;
        r.anim_levels = st.per_anim_level;
        r.geom_methods = st.per_geom_method;
        r.walk_methods = st.per_walk_method;
        r.lod = sample_lod(world);
        if (s.renderer) {
            r.gpu = sample_gpu(*s.renderer);
            r.gpu.drawn_twice = world.render_lists().drawn_twice;
        }
        if (fidelity) {
            auto fr = fidelity->measure();
            if (!fr.ok()) {
                print_error(fr.error().to_string());
                return 1;
            }
            r.fidelity = fr.value();
        }
        records.push_back(std::move(r));
        if (!options.quiet) progress(f + 1, frames, tty, "profile ");
    }
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    // With --gpu-overlap on the last frames are still being drawn: wait for them outside the measured frames.
    if (Status st = world.finish_rendering(); !st.ok()) {
        print_error(st.error().to_string());
        return 1;
    }
    const std::vector<GeometryWork> work_after = geometry_work(world);
    world.scheduler().set_trace_sink(nullptr);

    // ---- LOD off, same scene, same process: the slowdown ratio of the CPU systems.
    nlohmann::json compare = nullptr;
    if (options.compare_lod)
        compare = compare_lod_off(options, summarize(series_of(records, [](const FrameRecord& r) { return r.cpu_ms; })),
                                  [&](size_t done, size_t total) { if (!options.quiet) progress(done, total, isatty(2), "lod off "); });

    // ---- report.json
    nlohmann::json report;
    report["scene"] = options.scene;
    report["characters"] = world.character_count();
    report["frames"] = frames;
    report["warmup"] = options.warmup;
    report["threads"] = options.threads;
    // Overlapped: a frame's GPU figures are those of the newest frame finished when it ended (one or two back).
    const size_t overlapped = static_cast<size_t>(std::count_if(records.begin(), records.end(), [](const FrameRecord& r) { return r.overlapped; }));
    report["gpu_overlap"] = {{"mode", gpu_overlap_name(render ? world.options().overlap_gpu : GpuOverlap::Off)},
                             {"frames_overlapped", overlapped}};
    report["lod"] = options.lod;
    report["budget_ms"] = options.budget_ms ? nlohmann::json(*options.budget_ms) : nlohmann::json(nullptr);
    {
        std::vector<LodSample> lod;
        for (const auto& r : records) lod.push_back(r.lod);
        add_lod_report(world, lod, s.scene.dt, report);
    }
    report["viewport"] = {s.scene.width, s.scene.height};
    report["device"] = s.context ? s.context->device_name() : std::string("none (--no-render)");
    report["wall_seconds"] = wall_s;
    report["state_hash"] = state_hash(world);
    report["plan"] = sched.passes();
    auto series = [&](auto get) {
        std::vector<double> v;
        for (const auto& r : records) v.push_back(get(r));
        return v;
    };
    nlohmann::json sys = nlohmann::json::object();
    for (uint32_t i = 0; i < systems; ++i)
        sys[sched.names()[i]] = to_json(summarize(series([&](const FrameRecord& r) { return r.system_ms[i]; })));
    report["systems"] = sys;
    const auto cpu = summarize(series([](const FrameRecord& r) { return r.cpu_ms; }));
    const auto rnd = summarize(series([](const FrameRecord& r) { return r.render_ms; }));
    const auto gpu = summarize(series([](const FrameRecord& r) { return r.gpu_ms; }));
    const auto frame = summarize(series([](const FrameRecord& r) { return r.frame_ms; }));
    report["cpu_systems_ms"] = to_json(cpu);
    {  // the CPU systems only, as in cpu_ms
        std::vector<std::string> names;
        for (uint32_t i = 0; i < systems; ++i)
            if (!is_render[i]) names.push_back(sched.names()[i]);
        report["switch_hitch"] = switch_hitch_report(series_of(records, [&](const FrameRecord& r) {
            HitchFrame h{r.cpu_ms, r.lod.geom_switches + r.lod.anim_switches, {}};
            for (uint32_t i = 0; i < systems; ++i)
                if (!is_render[i]) h.system_ms.push_back(r.system_ms[i]);
            return h;
        }), names);
    }
    report["render_ms"] = to_json(rnd);
    report["gpu_ms"] = render ? to_json(gpu) : nlohmann::json(nullptr);
    report["frame_ms"] = to_json(frame);
    // All threads' CPU time per step; with --gpu-overlap on a frame's GPU work spills into the next step's.
    report["process_cpu_ms"] = to_json(summarize(series([](const FrameRecord& r) { return r.process_cpu_ms; })));
    if (render) report["render_passes"] = gpu_report(series_of(records, [](const FrameRecord& r) { return r.gpu; }));
    report["renderer"] = s.renderer ? renderer_report(s.renderer->resolved_options(), world.options().impostor_elevations)
                                    : nlohmann::json(nullptr);
    nlohmann::json levels;
    std::vector<std::string> gnames, anames;
    for (const auto& l : table.geom_levels) gnames.push_back(l.name);
    for (const auto& l : table.anim_levels) anames.push_back(l.name);
    levels["geometric"] = gnames;
    levels["animation"] = anames;
    levels["geometric_methods"] = {"hidden", "rigid_proxy", "skinned_mesh", "layered", "subdivided"};
    levels["walk_methods"] = {"clip", "kinematic", "dynamic"};
    report["levels"] = levels;
    nlohmann::json atlases = nlohmann::json::array();  // impostor atlases baked at load (one per type)
    for (const World::ImpostorReport& a : world.impostor_atlases())
        atlases.push_back({{"type", a.type}, {"width", a.width}, {"height", a.height}, {"build_ms", a.build_ms},
                           {"texture_bytes", a.texture_bytes}, {"cached", a.cached}, {"shared_from", a.shared_from},
                           {"scale", a.scale}, {"distance_px", a.distance_px}});
    report["impostor_atlases"] = atlases;
    report["bake_cache"] = bake_cache_report(world);
    nlohmann::json per_frame = nlohmann::json::array();
    for (const auto& r : records)
        per_frame.push_back({{"geometric", r.geom_levels}, {"animation", r.anim_levels},
                             {"geometric_methods", r.geom_methods}, {"walk_methods", r.walk_methods}});
    report["characters_per_level_per_frame"] = per_frame;
    nlohmann::json mem = nlohmann::json::object();
    const auto bytes = memory_per_level(world);
    for (size_t l = 0; l < bytes.size() && l < gnames.size(); ++l) mem[gnames[l]] = bytes[l];
    report["memory_bytes_per_character_per_level"] = mem;
    report["geometry_work"] = geometry_work_report(world, work_before, work_after, frames);
    report["lod_stats_last_frame"] = to_json(world.lod_stats(), table);
    nlohmann::json explain = nlohmann::json::array();
    const size_t n = world.character_count();
    for (size_t k = 0; k < 5 && n > 0; ++k) explain.push_back(world.explain(static_cast<uint32_t>(k * (n - 1) / 4)));
    report["explain_sample"] = explain;
    if (options.compare_lod) report["lod_off_comparison"] = compare;
    if (motion) report["motion_metrics"] = motion->report(table);
    if (fidelity) report["fidelity"] = fidelity_report(records.empty() ? std::vector<FidelityFrame>{} : [&] {
        std::vector<FidelityFrame> v;
        for (const auto& r : records) v.push_back(r.fidelity);
        return v;
    }(), gnames);
    {
        std::ofstream f(out + "/report.json");
        f << report.dump(2) << "\n";
        if (!f) {
            print_error("cannot write " + out + "/report.json");
            return 1;
        }
    }
    // ---- frames.csv
    {
        std::ofstream f(out + "/frames.csv");
        f << "frame,cpu_systems_ms,render_ms,gpu_ms,frame_ms";
        for (const auto& name : sched.names()) f << ",system_" << name << "_ms";  // apart from the totals
        for (const auto& g : gnames) f << ",geom_" << g;
        for (const auto& a : anames) f << ",anim_" << a;
        if (fidelity) f << ",mean_deviation_px,mean_moving_reference_deviation_px,max_deviation_px,psnr_db,change_px,switches,error_change,error_change_in_switches,reference_change";
        f << ",animation_ms,geometry_ms,geom_switches,anim_switches,visible,occluded,process_cpu_ms,gpu_overlapped\n";
        for (size_t i = 0; i < records.size(); ++i) {
            const auto& r = records[i];
            f << i << "," << r.cpu_ms << "," << r.render_ms << "," << r.gpu_ms << "," << r.frame_ms;
            for (double v : r.system_ms) f << "," << v;
            for (size_t l = 0; l < gnames.size(); ++l) f << "," << (l < r.geom_levels.size() ? r.geom_levels[l] : 0);
            for (size_t l = 0; l < anames.size(); ++l) f << "," << (l < r.anim_levels.size() ? r.anim_levels[l] : 0);
            if (fidelity)
                f << "," << r.fidelity.mean_deviation_px << "," << r.fidelity.mean_moving_deviation_px << "," << r.fidelity.max_deviation_px << "," << r.fidelity.psnr_db
                  << "," << r.fidelity.changed_fraction << "," << r.fidelity.switches << "," << r.fidelity.error_change << ","
                  << r.fidelity.error_change_in_switches << "," << r.fidelity.reference_changed_fraction;
            f << "," << r.lod.animation_ms << "," << r.lod.geometry_ms << "," << r.lod.geom_switches << ","
              << r.lod.anim_switches << "," << r.lod.visible << "," << r.lod.occluded << "," << r.process_cpu_ms << ","
              << (r.overlapped ? 1 : 0) << "\n";
        }
    }
    // ---- trace.json
    std::vector<std::string> trace_names = sched.names();
    const auto render_system = std::find(trace_names.begin(), trace_names.end(), "render");
    if (render && render_system != trace_names.end())
        add_gpu_trace(series_of(records, [](const FrameRecord& r) { return r.gpu; }),
                      static_cast<uint32_t>(render_system - trace_names.begin()), trace, trace_names);
    if (Status st = write_chrome_trace(out + "/trace.json", trace, trace_names); !st.ok()) {
        print_error(st.error().to_string());
        return 1;
    }
    // ---- frame_times.svg
    {
        std::vector<PlotSeries> plot = {{"CPU systems (ms)", series([](const FrameRecord& r) { return r.cpu_ms; }), "#1f77b4"},
                                        {"whole frame (ms)", series([](const FrameRecord& r) { return r.frame_ms; }), "#2ca02c"}};
        if (render) plot.push_back({"render incl. GPU wait (ms)", series([](const FrameRecord& r) { return r.render_ms; }), "#ff7f0e"});
        write_svg_plot(out + "/frame_times.svg", "aloha profile: " + s.scene.name + " (" + std::to_string(n) + " characters)",
                       "milliseconds", plot, render ? 33.3 : 16.7);
    }
    if (render) {
        if (Status st = save_frame(s, out + "/last_frame.png"); !st.ok()) {
            print_error(st.error().to_string());
            return 1;
        }
    }
    if (Status v = check_validation(s); !v.ok()) {
        print_error(v.error().to_string());
        return 1;
    }
    // ---- summary table
    std::cout << "\n" << s.scene.name << ": " << n << " characters, " << frames << " frames (+" << options.warmup
              << " warm-up), lod " << (options.lod ? "on" : "off") << ", " << (render ? s.context->device_name() : "no render")
              << (render ? gpu_overlap_line(world.options().overlap_gpu, overlapped, frames) : std::string()) << "\n";
    std::cout << std::left << std::setw(22) << "system" << std::right << std::setw(10) << "mean" << std::setw(10) << "p50"
              << std::setw(10) << "p95" << std::setw(10) << "p99" << std::setw(10) << "max" << "  (ms)\n";
    auto row = [&](const std::string& name, const SeriesStats& st) {
        std::cout << std::left << std::setw(22) << name << std::right << std::setw(10) << fmt(st.mean) << std::setw(10)
                  << fmt(st.p50) << std::setw(10) << fmt(st.p95) << std::setw(10) << fmt(st.p99) << std::setw(10)
                  << fmt(st.max) << "\n";
    };
    for (uint32_t i = 0; i < systems; ++i)
        row(sched.names()[i], summarize(series([&](const FrameRecord& r) { return r.system_ms[i]; })));
    row("= CPU systems", cpu);
    std::cout << switch_hitch_line(report["switch_hitch"]);
    if (render) {
        row("GPU (timestamps)", gpu);
        std::cout << gpu_table(report["render_passes"]);
    }
    row("= whole frame", frame);
    row("process CPU (threads)", summarize(series([](const FrameRecord& r) { return r.process_cpu_ms; })));
    if (options.compare_lod) {
        if (compare.contains("error")) std::cout << "LOD off: " << compare["error"].get<std::string>() << "\n";
        else std::cout << "LOD off: CPU systems mean " << fmt(compare["cpu_systems_ms"]["mean"].get<double>()) << " ms, "
                       << fmt(compare["ratio_mean"].get<double>()) << "x slower than LOD on (target 20x)\n";
    }
    for (const World::ImpostorReport& a : world.impostor_atlases()) {
        if (!a.shared_from.empty()) {
            std::cout << "impostor atlas '" << a.type << "': '" << a.shared_from << "''s drawn " << fmt(a.scale) << "x (surfaces within "
                      << fmt(a.distance_px) << " of its pixels), " << fmt(a.build_ms) << " ms to compare\n";
            continue;
        }
        std::cout << "impostor atlas '" << a.type << "': " << a.width << " x " << a.height << " px, " << fmt(a.build_ms) << (a.cached ? " ms from the bake cache, " : " ms to bake, ")
                  << fmt(double(a.texture_bytes) / 1048576.0) << " MiB with mips\n";
    }
    std::cout << bake_cache_line(world);
    if (report["renderer"].is_object()) std::cout << renderer_line(report["renderer"]);
    std::cout << lod_summary(report);
    if (motion) std::cout << motion->table(table);
    if (fidelity) std::cout << fidelity_summary(report["fidelity"]);
    std::cout << "state hash " << state_hash(world) << "; reports in " << out << "/\n";
    return 0;
}

}  // namespace aloha::tool
