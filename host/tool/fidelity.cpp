#include "host/scene/world_diagnostics.hpp"
#include "host/tool/fidelity.hpp"

#include "host/tool/session.hpp"
#include "host/tool/stats.hpp"

#include <cmath>

namespace aloha::tool {

namespace {

// PSNR of two RGBA8 images over RGB (dB); identical images give 99.
double psnr(const gpu::Rgba8Image& a, const gpu::Rgba8Image& b) {
    double se = 0.0;
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.pixels.size() && i + 3 < b.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.pixels[i + c]) - double(b.pixels[i + c]);
            se += d * d;
            ++n;
        }
    if (n == 0 || se == 0.0) return 99.0;
    const double mse = se / double(n);
    return 10.0 * std::log10(255.0 * 255.0 / mse);
}

// Mean absolute RGB change between two frames, as a fraction of full scale.
double mean_change(const gpu::Rgba8Image& a, const gpu::Rgba8Image& b) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.pixels.size() && i + 3 < b.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c) sum += std::abs(double(a.pixels[i + c]) - double(b.pixels[i + c])), ++n;
    return n ? sum / (255.0 * double(n)) : 0.0;
}

class Probe final : public FidelityProbe {
public:
    explicit Probe(Session& s) : s_(s) {}

    Status init() {
        auto target = gpu::OffscreenTarget::create(*s_.context, s_.scene.width, s_.scene.height);
        if (!target.ok()) return target.error();
        reference_target_ = std::move(target.value());
        return {};
    }

    Result<FidelityFrame> measure() override {
        World& world = *s_.world;
        auto lod = s_.target.read_back(*s_.context);
        if (!lod.ok()) return lod.error();
        if (Status st = reference_frame(world, frame_); !st.ok()) return st.error();
        FrameInput input;
        world.frame_settings(input);
        input.meshes = frame_.meshes;
        if (Status st = s_.renderer->render(input, reference_target_); !st.ok()) return st.error();
        if (Status st = s_.renderer->finish(); !st.ok()) return st.error();
        auto reference = reference_target_.read_back(*s_.context);
        if (!reference.ok()) return reference.error();
        FidelityFrame out;
        double sum = 0.0;
        uint64_t count = 0;
        for (size_t l = 0; l < frame_.deviation_sum.size(); ++l) {
            const uint64_t n = frame_.deviation_count[l];
            out.mean_deviation_per_level.push_back(n ? frame_.deviation_sum[l] / double(n) : -1.0);
            out.max_deviation_per_level.push_back(n ? frame_.deviation_max[l] : -1.0);
            sum += frame_.deviation_sum[l];
            count += n;
            out.max_deviation_px = std::max(out.max_deviation_px, frame_.deviation_max[l]);
        }
        out.mean_deviation_px = count ? sum / double(count) : 0.0;
        out.psnr_db = psnr(lod.value(), reference.value());
        out.changed_fraction = previous_.pixels.empty() ? 0.0 : mean_change(lod.value(), previous_);
        out.switches = frame_.switches;
        previous_ = std::move(lod.value());
        return out;
    }

private:
    Session& s_;
    gpu::OffscreenTarget reference_target_;
    ReferenceFrame frame_;
    gpu::Rgba8Image previous_;
};

}  // namespace

Result<std::unique_ptr<FidelityProbe>> FidelityProbe::create(Session& session) {
    if (!session.context || !session.renderer) return make_error("", "--fidelity needs the renderer");
    auto probe = std::make_unique<Probe>(session);
    if (Status s = probe->init(); !s.ok()) return s.error();
    return std::unique_ptr<FidelityProbe>(std::move(probe));
}

nlohmann::json fidelity_report(const std::vector<FidelityFrame>& frames) {
    nlohmann::json j;
    std::vector<double> mean, max, psnr_values, ordinary, at_switch;
    size_t levels = 0;
    for (const auto& f : frames) levels = std::max(levels, f.mean_deviation_per_level.size());
    std::vector<double> level_sum(levels, 0.0), level_max(levels, 0.0);
    std::vector<size_t> level_frames(levels, 0);
    for (size_t k = 0; k < frames.size(); ++k) {
        const FidelityFrame& f = frames[k];
        mean.push_back(f.mean_deviation_px);
        max.push_back(f.max_deviation_px);
        psnr_values.push_back(f.psnr_db);
        if (k > 0) (f.switches > 0 ? at_switch : ordinary).push_back(f.changed_fraction);
        for (size_t l = 0; l < f.mean_deviation_per_level.size(); ++l) {
            if (f.mean_deviation_per_level[l] < 0) continue;
            level_sum[l] += f.mean_deviation_per_level[l];
            level_max[l] = std::max(level_max[l], f.max_deviation_per_level[l]);
            ++level_frames[l];
        }
    }
    j["mean_deviation_px"] = to_json(summarize(mean));
    j["max_deviation_px"] = to_json(summarize(max));
    j["psnr_db"] = to_json(summarize(psnr_values));
    nlohmann::json per_level = nlohmann::json::array();
    for (size_t l = 0; l < levels; ++l)
        per_level.push_back(level_frames[l] ? nlohmann::json{{"level", l}, {"mean_px", level_sum[l] / double(level_frames[l])},
                                                             {"max_px", level_max[l]}}
                                            : nlohmann::json{{"level", l}, {"mean_px", nullptr}, {"max_px", nullptr}});
    j["deviation_per_level"] = per_level;
    const SeriesStats ord = summarize(ordinary), sw = summarize(at_switch);
    j["popping"] = {{"ordinary_frames", ord.count},
                    {"switch_frames", sw.count},
                    {"ordinary_change_p95", ord.p95},
                    {"switch_change_max", sw.max},
                    {"switch_no_worse_than_ordinary_p95", sw.count == 0 || sw.max <= ord.p95}};
    const double overall_mean = mean.empty() ? 0.0 : summarize(mean).mean;
    j["target_mean_deviation_under_1px"] = overall_mean < 1.0;
    j["note"] = "Deviation compares each mesh-level character's displayed control surface with its level-0 control "
                "surface (springs at rest), projected to pixels; rigid proxies and hidden characters have no skin to "
                "compare and count only in the PSNR, whose reference renders every visible character at the richest "
                "layered level.";
    return j;
}

}  // namespace aloha::tool
