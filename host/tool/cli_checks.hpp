// The checks behind the aloha command line's options (CLI11 validators) and the parsers of the list
// values they accept. Each check names what it expects and the value it got.
#pragma once

#include "engine/core/result.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace aloha::tool {

/// An Error located at "command line".
Error cli_error(const std::string& message);

/// A whole number in [lo, hi].
CLI::Validator whole_number(uint32_t lo, uint32_t hi);
/// Any whole number that fits 64 bits (seeds).
CLI::Validator whole_number_u64();
/// A number of milliseconds in (0, 10000).
CLI::Validator milliseconds();
/// A number of atlas pixels in [0, 96] (--impostor-share).
[[nodiscard]] CLI::Validator atlas_pixels();
/// "on" or "off".
CLI::Validator on_off();
/// A non-empty value.
CLI::Validator non_empty();
/// One of `choices`.
CLI::Validator one_of(std::vector<std::string> choices);
/// A comma list whose every item is one of `choices`.
CLI::Validator member_list(std::vector<std::string> choices);
/// Comma-separated whole numbers in [1, 1000000] (crowd sizes).
CLI::Validator count_list();
/// Comma list of indices and inclusive ranges, e.g. "0,5,10-20".
CLI::Validator index_ranges();
/// "A:B" with 0 <= A < B <= 10000000, or a count N meaning 0:N.
CLI::Validator frame_range();

/// The values of a list accepted by count_list().
std::vector<uint32_t> parse_count_list(const std::string& text);
/// The ranges of a list accepted by index_ranges().
std::vector<std::pair<uint32_t, uint32_t>> parse_index_ranges(const std::string& text);
/// The range of a value accepted by frame_range().
std::pair<uint32_t, uint32_t> parse_frame_range(const std::string& text);

}  // namespace aloha::tool
