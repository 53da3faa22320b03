#include "host/tool/stats.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

namespace aloha::tool {

SeriesStats summarize(std::span<const double> values) {
    SeriesStats s;
    s.count = values.size();
    if (values.empty()) return s;
    std::vector<double> v(values.begin(), values.end());
    std::sort(v.begin(), v.end());
    auto rank = [&](double q) {
        const size_t r = static_cast<size_t>(std::ceil(q * static_cast<double>(v.size())));
        return v[std::min(v.size() - 1, r == 0 ? 0 : r - 1)];
    };
    s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    s.p50 = rank(0.50);
    s.p95 = rank(0.95);
    s.p99 = rank(0.99);
    s.max = v.back();
    s.min = v.front();
    return s;
}

nlohmann::json to_json(const SeriesStats& s) {
    return {{"mean", s.mean}, {"p50", s.p50}, {"p95", s.p95}, {"p99", s.p99}, {"max", s.max}, {"min", s.min},
            {"count", s.count}};
}

bool write_svg_plot(const std::string& path, const std::string& title, const std::string& y_label,
                    std::span<const PlotSeries> series, double reference_line) {
    const double W = 960, H = 420, L = 70, R = 20, T = 40, B = 50;
    double ymax = reference_line > 0 ? reference_line * 1.1 : 0.0;
    size_t n = 1;
    for (const auto& s : series) {
        n = std::max(n, s.values.size());
        for (double v : s.values) ymax = std::max(ymax, v);
    }
    if (ymax <= 0) ymax = 1;
    ymax *= 1.05;
    auto x = [&](size_t i) { return L + (W - L - R) * (n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0); };
    auto y = [&](double v) { return T + (H - T - B) * (1.0 - v / ymax); };
    std::ostringstream o;
    o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' font-family='sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << W / 2 << "' y='22' text-anchor='middle' font-size='15'>" << title << "</text>\n"
      << "<text x='16' y='" << H / 2 << "' transform='rotate(-90 16 " << H / 2 << ")' text-anchor='middle'>" << y_label << "</text>\n"
      << "<text x='" << W / 2 << "' y='" << H - 12 << "' text-anchor='middle'>frame</text>\n";
    for (int g = 0; g <= 5; ++g) {
        const double v = ymax * g / 5.0;
        o << "<line x1='" << L << "' x2='" << W - R << "' y1='" << y(v) << "' y2='" << y(v) << "' stroke='#ddd'/>"
          << "<text x='" << L - 6 << "' y='" << y(v) + 4 << "' text-anchor='end'>" << std::round(v * 100) / 100 << "</text>\n";
    }
    if (reference_line > 0)
        o << "<line x1='" << L << "' x2='" << W - R << "' y1='" << y(reference_line) << "' y2='" << y(reference_line)
          << "' stroke='#c00' stroke-dasharray='6 4'/>\n";
    double legend_y = T + 4;
    for (const auto& s : series) {
        o << "<polyline fill='none' stroke='" << s.colour << "' stroke-width='1.2' points='";
        for (size_t i = 0; i < s.values.size(); ++i) o << x(i) << ',' << y(s.values[i]) << ' ';
        o << "'/>\n<text x='" << L + 10 << "' y='" << legend_y + 10 << "' fill='" << s.colour << "'>" << s.name << "</text>\n";
        legend_y += 16;
    }
    o << "</svg>\n";
    std::ofstream f(path);
    f << o.str();
    return static_cast<bool>(f);
}

}  // namespace aloha::tool
