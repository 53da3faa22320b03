#include "host/tool/cli_checks.hpp"

#include <charconv>
#include <cmath>
#include <optional>

namespace aloha::tool {

namespace {

template <class T>
bool parse_number(const std::string& text, T& out) {
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, out);
    return ec == std::errc() && p == end;
}

// Splits a comma list; empty items are kept so that "1,,2" can be refused.
std::vector<std::string> split_commas(const std::string& text) {
    std::vector<std::string> items;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        items.push_back(text.substr(start, comma - start));
        start = comma + 1;
    }
    return items;
}

std::optional<std::pair<uint32_t, uint32_t>> index_range(const std::string& item) {
    const size_t dash = item.find('-');
    uint32_t lo = 0, hi = 0;
    const bool ok = dash == std::string::npos ? parse_number(item, lo) && (hi = lo, true)
                                              : parse_number(item.substr(0, dash), lo) && parse_number(item.substr(dash + 1), hi);
    if (!ok || hi < lo) return std::nullopt;
    return std::pair{lo, hi};
}

std::optional<std::pair<uint32_t, uint32_t>> frames_range(const std::string& value) {
    const size_t colon = value.find(':');
    uint32_t a = 0, b = 0;
    const bool ok = colon == std::string::npos ? parse_number(value, b)
                                               : parse_number(value.substr(0, colon), a) && parse_number(value.substr(colon + 1), b);
    if (!ok || b <= a || b > 10'000'000) return std::nullopt;
    return std::pair{a, b};
}

CLI::Validator check(std::function<std::string(const std::string&)> test, const std::string& what) {
    return CLI::Validator([test](std::string& value) { return test(value); }, what);
}

}  // namespace

Error cli_error(const std::string& message) { return make_error("command line", message); }

CLI::Validator whole_number(uint32_t lo, uint32_t hi) {
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    return check([lo, hi, range](const std::string& v) {
        uint32_t n = 0;
        return parse_number(v, n) && n >= lo && n <= hi ? "" : "expects a whole number in " + range + ", got '" + v + "'";
    }, "UINT in " + range);
}

CLI::Validator whole_number_u64() {
    return check([](const std::string& v) {
        uint64_t n = 0;
        return parse_number(v, n) ? "" : "expects a whole number, got '" + v + "'";
    }, "UINT64");
}

CLI::Validator milliseconds() {
    return check([](const std::string& v) {
        double d = 0;
        return parse_number(v, d) && d > 0.0 && d < 10000.0 ? "" : "expects a number of milliseconds in (0, 10000), got '" + v + "'";
    }, "MS");
}

CLI::Validator atlas_pixels() {
    return check([](const std::string& v) {
        double d = 0;
        return parse_number(v, d) && d >= 0.0 && d <= 96.0 ? "" : "expects a number of atlas pixels in [0, 96], got '" + v + "'";
    }, "PX");
}

CLI::Validator on_off() { return one_of({"on", "off"}); }

CLI::Validator non_empty() {
    return check([](const std::string& v) { return v.empty() ? std::string("needs a non-empty value") : ""; }, "TEXT");
}

CLI::Validator one_of(std::vector<std::string> choices) {
    std::string names;
    for (size_t i = 0; i < choices.size(); ++i) names += (i ? (i + 1 == choices.size() ? " or " : ", ") : "") + choices[i];
    return check([choices, names](const std::string& v) {
        for (const std::string& c : choices)
            if (v == c) return std::string();
        return "expects " + names + ", got '" + v + "'";
    }, names);
}

CLI::Validator member_list(std::vector<std::string> choices) {
    std::string names;
    for (size_t i = 0; i < choices.size(); ++i) names += (i ? ", " : "") + choices[i];
    return check([choices, names](const std::string& v) {
        for (const std::string& item : split_commas(v)) {
            bool known = false;
            for (const std::string& c : choices) known = known || item == c;
            if (!known) return "expects a comma list of " + names + ", got '" + v + "'";
        }
        return std::string();
    }, "LIST of " + names);
}

CLI::Validator count_list() {
    return check([](const std::string& v) {
        for (const std::string& item : split_commas(v)) {
            uint32_t n = 0;
            if (!parse_number(item, n) || n < 1 || n > 1'000'000)
                return "expects comma-separated whole numbers in [1, 1000000], got '" + v + "'";
        }
        return std::string();
    }, "COUNTS");
}

CLI::Validator index_ranges() {
    return check([](const std::string& v) {
        for (const std::string& item : split_commas(v))
            if (!index_range(item))
                return "expects a comma list of character indices and ranges (e.g. 0,5,10-20), got '" + v +
                       "' (bad item '" + item + "')";
        return std::string();
    }, "LIST");
}

CLI::Validator frame_range() {
    return check([](const std::string& v) {
        return frames_range(v) ? std::string()
                               : "expects A:B with 0 <= A < B <= 10000000 (frames A to B-1) or a frame count N, got '" + v + "'";
    }, "A:B");
}

std::vector<uint32_t> parse_count_list(const std::string& text) {
    std::vector<uint32_t> counts;
    for (const std::string& item : split_commas(text)) {
        uint32_t n = 0;
        if (parse_number(item, n)) counts.push_back(n);
    }
    return counts;
}

std::vector<std::pair<uint32_t, uint32_t>> parse_index_ranges(const std::string& text) {
    std::vector<std::pair<uint32_t, uint32_t>> ranges;
    for (const std::string& item : split_commas(text))
        if (auto r = index_range(item)) ranges.push_back(*r);
    return ranges;
}

std::pair<uint32_t, uint32_t> parse_frame_range(const std::string& text) { return frames_range(text).value_or(std::pair{0u, 0u}); }

}  // namespace aloha::tool
