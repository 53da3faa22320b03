// Summary statistics for the profiler: mean and percentiles of per-frame times.
#pragma once

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <vector>

namespace aloha::tool {

/// Mean, percentiles and maximum of a series (milliseconds).
struct SeriesStats {
    double mean = 0, p50 = 0, p95 = 0, p99 = 0, max = 0, min = 0;
    size_t count = 0;
};

/// Computes SeriesStats; percentiles by nearest rank on a sorted copy. Empty input gives zeros.
SeriesStats summarize(std::span<const double> values);

/// SeriesStats as a JSON object {mean, p50, p95, p99, max, min, count}.
nlohmann::json to_json(const SeriesStats& s);

/// One line of a named series for an SVG plot.
struct PlotSeries {
    std::string name;
    std::vector<double> values;
    std::string colour;  ///< CSS colour
};

/// Writes a simple line plot (x = index, y = value) as SVG to `path`; returns false on I/O failure.
bool write_svg_plot(const std::string& path, const std::string& title, const std::string& y_label,
                    std::span<const PlotSeries> series, double reference_line = -1.0);

}  // namespace aloha::tool
