// `aloha scale`: frame time against crowd size (the scene's crowds rescaled to each count).
#include "host/tool/commands.hpp"
#include "host/tool/session.hpp"
#include "host/tool/stats.hpp"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

namespace aloha::tool {

int run_scale(const CliOptions& options) {
    const std::string out = options.out.empty() ? "out/scale" : options.out;
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(out + "/scaling.json", ec) && !options.force) {
        print_error(out + "/scaling.json already exists; pass --force to overwrite it");
        return 1;
    }
    fs::create_directories(out, ec);
    if (ec) {
        print_error("cannot create output folder " + out + ": " + ec.message());
        return 1;
    }
    nlohmann::json rows = nlohmann::json::array();
    PlotSeries cpu_p95{"CPU systems p95 (ms)", {}, "#1f77b4"}, frame_p95{"whole frame p95 (ms)", {}, "#2ca02c"};
    std::cout << std::setw(10) << "characters" << std::setw(14) << "cpu mean" << std::setw(12) << "cpu p95"
              << std::setw(14) << "frame p95" << std::setw(18) << "cpu us/character" << "\n";
    for (uint32_t count : options.counts) {
        CliOptions o = options;
        o.characters = count;
        auto opened = open_session(o, !options.no_render);
        if (!opened.ok()) {
            print_error(opened.error().to_string());
            return 1;
        }
        Session& s = *opened.value();
        World& world = *s.world;
        const Scheduler& sched = world.scheduler();
        const uint32_t frames = options.frames.value_or(120);
        for (uint32_t f = 0; f < options.warmup; ++f) world.step();
        std::vector<double> cpu, frame;
        for (uint32_t f = 0; f < frames; ++f) {
            world.step();
            cpu.push_back(world.last_cpu_ms());
            frame.push_back(static_cast<double>(sched.frame_timings().latest()) * 1e-6);
        }
        const SeriesStats c = summarize(cpu), fr = summarize(frame);
        rows.push_back({{"characters", count}, {"cpu_systems_ms", to_json(c)}, {"frame_ms", to_json(fr)},
                        {"cpu_us_per_character", c.mean * 1000.0 / count}});
        cpu_p95.values.push_back(c.p95);
        frame_p95.values.push_back(fr.p95);
        std::cout << std::setw(10) << count << std::setw(14) << std::fixed << std::setprecision(3) << c.mean
                  << std::setw(12) << c.p95 << std::setw(14) << fr.p95 << std::setw(18) << c.mean * 1000.0 / count << "\n";
    }
    std::ofstream(out + "/scaling.json") << nlohmann::json{{"scene", options.scene}, {"rows", rows}}.dump(2) << "\n";
    {
        std::ofstream csv(out + "/scaling.csv");
        csv << "characters,cpu_mean_ms,cpu_p95_ms,frame_p95_ms\n";
        for (const auto& r : rows)
            csv << r["characters"] << "," << r["cpu_systems_ms"]["mean"] << "," << r["cpu_systems_ms"]["p95"] << ","
                << r["frame_ms"]["p95"] << "\n";
    }
    std::vector<PlotSeries> plot = {cpu_p95};
    if (!options.no_render) plot.push_back(frame_p95);
    write_svg_plot(out + "/scaling.svg", "frame time against crowd size (x: run index, counts " + [&] {
        std::string c;
        for (uint32_t n : options.counts) c += (c.empty() ? "" : ",") + std::to_string(n);
        return c;
    }() + ")", "milliseconds", plot);
    std::cout << "wrote " << out << "/scaling.{json,csv,svg}\n";
    return 0;
}

}  // namespace aloha::tool
