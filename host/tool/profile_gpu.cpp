#include "host/tool/profile_gpu.hpp"

#include "host/tool/stats.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

namespace aloha::tool {

GpuSample sample_gpu(const CrowdRenderer& renderer) {
    GpuSample s;
    s.upload_ms = renderer.last_upload_ms();
    s.upload_bytes = renderer.last_upload_bytes();
    s.draws = renderer.last_draw_count();
    s.gpu_ms = renderer.last_gpu_ms();
    s.passes.assign(renderer.last_gpu_passes().begin(), renderer.last_gpu_passes().end());
    return s;
}

nlohmann::json gpu_report(const std::vector<GpuSample>& samples) {
    std::vector<double> upload, mib, draws, twice;
    struct Pass {
        std::vector<double> ms;
        double draws = 0, instances = 0, triangles = 0;
        size_t order = 0;  // first appearance, for a stable listing
    };
    std::map<std::string, Pass> passes;
    for (const GpuSample& s : samples) {
        upload.push_back(s.upload_ms);
        mib.push_back(double(s.upload_bytes) / double(1 << 20));
        draws.push_back(s.draws);
        twice.push_back(s.drawn_twice);
        for (const GpuPassTime& p : s.passes) {
            auto [it, fresh] = passes.try_emplace(p.name);
            if (fresh) it->second.order = passes.size();
            it->second.ms.push_back(p.ms);
            it->second.draws += p.draws;
            it->second.instances += double(p.instances);
            it->second.triangles += double(p.triangles);
        }
    }
    nlohmann::json j;
    j["upload_ms"] = to_json(summarize(upload));
    j["upload_mib"] = to_json(summarize(mib));
    j["draws"] = to_json(summarize(draws));
    j["drawn_twice"] = to_json(summarize(twice));  // characters in a cross-fade (impostor + mesh or proxies)
    std::vector<std::pair<size_t, std::string>> order;
    for (const auto& [name, p] : passes) order.emplace_back(p.order, name);
    std::sort(order.begin(), order.end());
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [k, name] : order) {
        const Pass& p = passes[name];
        const double n = double(p.ms.size());
        nlohmann::json e = to_json(summarize(p.ms));
        e["name"] = name;
        e["frames"] = p.ms.size();
        e["mean_draws"] = p.draws / n;
        e["mean_instances"] = p.instances / n;
        e["mean_triangles"] = p.triangles / n;
        list.push_back(e);
    }
    j["passes"] = list;
    return j;
}

std::string gpu_table(const nlohmann::json& render_passes) {
    std::ostringstream o;
    auto fmt = [](double v) {
        std::ostringstream f;
        f << std::fixed << std::setprecision(v < 10 ? 3 : 2) << v;
        return f.str();
    };
    auto row = [&](const std::string& name, const nlohmann::json& st, const std::string& extra) {
        o << std::left << std::setw(22) << name << std::right;
        for (const char* k : {"mean", "p50", "p95", "p99", "max"}) o << std::setw(10) << fmt(st[k].get<double>());
        o << extra << "\n";
    };
    const nlohmann::json& mib = render_passes["upload_mib"];
    std::ostringstream up;
    up << "  " << fmt(mib["mean"].get<double>()) << " MiB, " << fmt(render_passes["draws"]["mean"].get<double>()) << " draws";
    if (render_passes.contains("drawn_twice"))
        up << ", " << fmt(render_passes["drawn_twice"]["mean"].get<double>()) << " drawn twice (max "
           << fmt(render_passes["drawn_twice"]["max"].get<double>()) << ")";
    row("  upload (CPU copy)", render_passes["upload_ms"], up.str());
    for (const auto& p : render_passes["passes"]) {
        std::ostringstream ex;
        ex << "  " << std::fixed << std::setprecision(0) << p["mean_triangles"].get<double>() << " tris, "
           << p["mean_instances"].get<double>() << " inst, " << std::setprecision(1) << p["mean_draws"].get<double>()
           << " draws";
        if (p["frames"].get<size_t>() != render_passes["upload_ms"]["count"].get<size_t>())
            ex << " (" << p["frames"].get<size_t>() << " frames)";
        row("  gpu: " + p["name"].get<std::string>(), p, ex.str());
    }
    return o.str();
}

nlohmann::json renderer_report(const RendererOptions& resolved, uint32_t impostor_elevations) {
    return {{"far_layer_px", resolved.far_layer_below_px.value_or(0.0f)},
            {"far_layer_meshes_px", resolved.far_layer_meshes_below_px.value_or(0.0f)},
            {"distant_layer_px", resolved.distant_layer_below_px},
            {"far_layer_alpha_test", resolved.far_layer_alpha_test},
            {"texture_mips", resolved.blend_texture_mips.value_or(true) ? "blend" : "nearest"},
            {"impostor_views", impostor_views_name(resolved.impostor_views.value_or(ImpostorViews::Nearest))},
            {"max_texture_side", resolved.max_texture_side},
            {"constant_fragments", resolved.constant_fragments},
            {"impostor_elevations", impostor_elevations}};
}

std::string renderer_line(const nlohmann::json& r) {
    std::ostringstream o;
    const auto px = [&](const char* key) {
        const double v = r[key].get<double>();
        return v > 0.0 ? "under " + std::to_string(static_cast<int>(std::lround(v))) + " px" : std::string("off");
    };
    o << "renderer: far layer " << px("far_layer_px") << " (meshes " << px("far_layer_meshes_px") << ", alpha test "
      << std::lround(100.0 * r["far_layer_alpha_test"].get<double>()) << "%), distant layer " << px("distant_layer_px")
      << ", texture mips " << r["texture_mips"].get<std::string>() << ", impostor views "
      << r["impostor_views"].get<std::string>() << ", " << r["impostor_elevations"].get<uint32_t>()
      << " bands of impostor views";
    if (r["constant_fragments"].get<bool>()) o << ", constant fragments";
    o << "\n";
    return o.str();
}

void add_gpu_trace(const std::vector<GpuSample>& samples, uint32_t render_system, std::vector<TraceEvent>& trace,
                   std::vector<std::string>& names) {
    std::map<uint64_t, uint64_t> render_end;  // frame -> end of the render system's run (ns)
    uint64_t first_frame = UINT64_MAX;
    for (const TraceEvent& e : trace)
        if (e.kind == TraceKind::System && e.system == render_system) {
            render_end[e.frame] = e.end_ns;
            first_frame = std::min(first_frame, e.frame);
        }
    if (first_frame == UINT64_MAX) return;
    const uint32_t base = static_cast<uint32_t>(names.size());
    std::map<std::string, uint32_t> ids;
    for (size_t f = 0; f < samples.size(); ++f) {
        const auto end = render_end.find(first_frame + f);
        if (end == render_end.end() || samples[f].passes.empty()) continue;
        const GpuPassTime& last = samples[f].passes.back();
        const double total_ms = last.begin_ms + last.ms;
        const uint64_t start = end->second - std::min<uint64_t>(end->second, uint64_t(total_ms * 1e6));
        for (const GpuPassTime& p : samples[f].passes) {
            auto [it, fresh] = ids.try_emplace(p.name, base + static_cast<uint32_t>(ids.size()));
            if (fresh) names.push_back("gpu: " + p.name);
            trace.push_back({it->second, 0, start + uint64_t(p.begin_ms * 1e6), start + uint64_t((p.begin_ms + p.ms) * 1e6),
                             first_frame + f, TraceKind::Gpu});
        }
    }
}

}  // namespace aloha::tool
