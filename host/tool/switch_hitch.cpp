#include "host/tool/switch_hitch.hpp"

#include "host/tool/stats.hpp"

#include <cassert>
#include <iomanip>
#include <sstream>

namespace aloha::tool {

namespace {

// One side of the reading: its frames' largest CPU time against the p95 of all frames.
nlohmann::json side(std::span<const HitchFrame> frames, double p95, double bar, int want_switch) {
    size_t count = 0;
    double max_ms = 0;
    for (const HitchFrame& f : frames) {
        if (want_switch >= 0 && (f.switches > 0) != (want_switch == 1)) continue;
        ++count;
        max_ms = std::max(max_ms, f.cpu_ms);
    }
    if (count == 0) return {{"frames", 0}, {"max_ms", nullptr}, {"max_over_p95", nullptr}, {"within_bar", nullptr}};
    const double ratio = p95 > 0 ? max_ms / p95 : 0.0;
    return {{"frames", count}, {"max_ms", max_ms}, {"max_over_p95", ratio}, {"within_bar", ratio <= bar}};
}

std::string ratio_text(const nlohmann::json& s) {
    if (s["max_over_p95"].is_null()) return "none";
    std::ostringstream o;
    o << std::fixed << std::setprecision(2) << s["max_over_p95"].get<double>() << "x (" << s["frames"].get<size_t>() << (s["frames"].get<size_t>() == 1 ? " frame)" : " frames)");
    return o.str();
}

}  // namespace

nlohmann::json switch_hitch_report(std::span<const HitchFrame> frames, std::span<const std::string> system_names, double bar) {
    if (frames.empty()) return nullptr;
    std::vector<double> cpu;
    for (const HitchFrame& f : frames) cpu.push_back(f.cpu_ms);
    const SeriesStats st = summarize(cpu);
    size_t worst = 0;
    for (size_t k = 1; k < frames.size(); ++k)
        if (frames[k].cpu_ms > frames[worst].cpu_ms) worst = k;
    const HitchFrame& w = frames[worst];
    assert(w.system_ms.size() == system_names.size());
    nlohmann::json worst_json = {{"index", worst}, {"cpu_ms", w.cpu_ms}, {"switches", w.switches}};
    if (!w.system_ms.empty()) {
        size_t s = 0;
        for (size_t i = 1; i < w.system_ms.size(); ++i)
            if (w.system_ms[i] > w.system_ms[s]) s = i;
        std::vector<double> of_system;
        for (const HitchFrame& f : frames) of_system.push_back(s < f.system_ms.size() ? f.system_ms[s] : 0.0);
        worst_json["system"] = system_names[s];
        worst_json["system_ms"] = w.system_ms[s];
        worst_json["system_p50_ms"] = summarize(of_system).p50;
    }
    return {{"p95_ms", st.p95},
            {"bar", bar},
            {"all", side(frames, st.p95, bar, -1)},
            {"with_switch", side(frames, st.p95, bar, 1)},
            {"without_switch", side(frames, st.p95, bar, 0)},
            {"worst_frame", worst_json}};
}

std::string switch_hitch_line(const nlohmann::json& r) {
    if (r.is_null()) return "";
    std::ostringstream o;
    o << "CPU systems max / p95 (bar " << std::defaultfloat << r["bar"].get<double>() << "x): all frames " << ratio_text(r["all"]) << ", frames with a level switch "
      << ratio_text(r["with_switch"]) << ", without " << ratio_text(r["without_switch"]);
    const nlohmann::json& w = r["worst_frame"];
    o << "; slowest frame " << w["index"].get<size_t>() << " (" << w["switches"].get<uint32_t>() << " switches)";
    o << std::fixed << std::setprecision(3);
    if (w.contains("system"))
        o << ": " << w["system"].get<std::string>() << " " << w["system_ms"].get<double>() << " ms against a median "
          << w["system_p50_ms"].get<double>() << " ms";
    o << "\n";
    return o.str();
}

}  // namespace aloha::tool
