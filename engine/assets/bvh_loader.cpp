#include "engine/assets/bvh_loader.hpp"

#include "engine/anim/skeleton.hpp"
#include "engine/assets/animation_remap.hpp"
#include "engine/assets/bvh_hierarchy.hpp"
#include "engine/assets/file_io.hpp"
#include "engine/assets/text_scan.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace aloha {

namespace {

using bvh_detail::Channel;

bool blank(std::string_view line) {
    for (char c : line)
        if (c != ' ' && c != '\t' && c != '\v' && c != '\f') return false;
    return true;
}

// Next non-blank line's tokens; false at end of text.
bool next_tokens(LineCursor& cursor, std::vector<TextToken>* toks, int* number) {
    std::string_view line;
    while (cursor.next(&line, number)) {
        if (blank(line)) continue;
        toks->clear();
        tokenize_line(line, *number, toks);
        return true;
    }
    return false;
}

// Value token of "Frames: N" / "Frame Time: t" (accepting "Frames :" and "Frames:N" spellings).
std::optional<TextToken> header_value(const std::vector<TextToken>& toks, std::string_view key) {
    std::string joined;
    size_t k = 0;
    for (; k < toks.size(); ++k) {
        joined += toks[k].text;
        if (joined.size() >= key.size()) break;
        joined += ' ';
    }
    if (joined.rfind(key, 0) != 0 || k >= toks.size()) return std::nullopt;
    TextToken value = toks[k];
    const size_t extra = joined.size() - key.size();  // "Frames:994" written without a space
    if (extra > 0) {
        value.text = value.text.substr(value.text.size() - extra);
        return k + 1 == toks.size() ? std::optional<TextToken>(value) : std::nullopt;
    }
    if (k + 2 != toks.size()) return std::nullopt;
    return toks[k + 1];
}

glm::quat axis_rotation(Channel c, float degrees) {
    const float r = glm::radians(degrees);
    const glm::vec3 axis = c == Channel::kXrotation ? glm::vec3(1, 0, 0) : c == Channel::kYrotation ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    return glm::angleAxis(r, axis);
}

std::string file_stem(const std::string& source_name) {
    const std::string stem = std::filesystem::path(source_name).stem().string();
    return stem.empty() ? source_name : stem;
}

}  // namespace

Result<BvhData> parse_bvh(std::string_view text, const std::string& source_name, const BvhOptions& options) {
    if (!(options.unit_scale > 0.0f) || !std::isfinite(options.unit_scale))
        return make_error(source_name, "BvhOptions::unit_scale must be a positive finite number");
    LineCursor cursor(text);
    Result<bvh_detail::Hierarchy> parsed = bvh_detail::parse_hierarchy(cursor, source_name, options);
    if (!parsed.ok()) return parsed.error();
    bvh_detail::Hierarchy& h = parsed.value();

    // Header: "Frames: N" then "Frame Time: t".
    std::vector<TextToken> toks;
    int number = h.motion_line;
    if (!next_tokens(cursor, &toks, &number)) return make_error(source_name, "missing 'Frames:' after MOTION (truncated file?)", number);
    const std::optional<TextToken> frames_tok = header_value(toks, "Frames:");
    if (!frames_tok) return make_error(source_name, "expected 'Frames: <count>'", number);
    const int frames_line = number;
    const std::optional<int64_t> frames = parse_int(frames_tok->text);
    if (!frames) return make_error(source_name, "Frames count '" + std::string(frames_tok->text) + "' is not an integer", number, frames_tok->column);
    if (*frames < 0) return make_error(source_name, "Frames count must be at least 0, got " + std::to_string(*frames), number, frames_tok->column);
    if (*frames > kMaxBvhFrames)
        return make_error(source_name, "Frames count " + std::to_string(*frames) + " exceeds the limit of " + std::to_string(kMaxBvhFrames), number, frames_tok->column);
    if (!next_tokens(cursor, &toks, &number)) return make_error(source_name, "missing 'Frame Time:' (truncated file?)", number);
    const std::optional<TextToken> time_tok = header_value(toks, "Frame Time:");
    if (!time_tok) return make_error(source_name, "expected 'Frame Time: <seconds>'", number);
    const std::optional<float> frame_time = parse_float(time_tok->text);
    if (!frame_time) return make_error(source_name, "Frame Time '" + std::string(time_tok->text) + "' is not a number", number, time_tok->column);
    // A skeleton-only file (Frames: 0) may say "Frame Time: 0": it has no frames to time.
    if (!std::isfinite(*frame_time) || *frame_time < 0.0f || (*frame_time == 0.0f && *frames > 0) || *frame_time > 10.0f)
        return make_error(source_name, "Frame Time must be in (0, 10] seconds, got '" + std::string(time_tok->text) + "'", number, time_tok->column);

    // Count the motion rows before allocating anything sized by Frames.
    {
        LineCursor counter = cursor;
        std::string_view line;
        int row_line = 0;
        int64_t rows = 0;
        while (counter.next(&line, &row_line)) {
            if (blank(line)) continue;
            if (++rows > *frames)
                return make_error(source_name, "more motion rows than 'Frames: " + std::to_string(*frames) + "' (line " +
                                                   std::to_string(frames_line) + ")", row_line);
        }
        if (rows < *frames)
            return make_error(source_name, "Frames says " + std::to_string(*frames) + " but only " + std::to_string(rows) +
                                               " motion rows follow (truncated file?)", frames_line);
    }

    const size_t joint_count = h.skeleton.joints.size();
    const size_t frame_count = static_cast<size_t>(*frames);
    std::vector<size_t> first_channel(joint_count, 0);
    std::vector<uint8_t> has_pos(joint_count, 0), has_rot(joint_count, 0);
    for (size_t j = 0, c = 0; j < joint_count; ++j) {
        first_channel[j] = c;
        for (Channel ch : h.channels[j]) (ch <= Channel::kZposition ? has_pos : has_rot)[j] = 1;
        c += h.channels[j].size();
    }
    RawAnimation raw;
    raw.name = file_stem(source_name);
    raw.tracks.resize(joint_count);
    // Every row holds total_channels numbers, each needing at least 2 bytes, so this reserve is
    // bounded by the text size (rows were counted above).
    for (size_t j = 0; j < joint_count; ++j) {
        if (has_pos[j]) raw.tracks[j].translations.values.reserve(frame_count);
        if (has_rot[j]) raw.tracks[j].rotations.values.reserve(frame_count);
    }

    std::vector<float> row(h.total_channels);
    std::string_view line;
    for (size_t f = 0; f < frame_count; ++f) {
        while (cursor.next(&line, &number) && blank(line)) {
        }
        size_t n = 0;
        std::optional<Error> bad;
        for_each_token(line, [&](std::string_view tok, int column) {
            if (n >= row.size()) {
                ++n;
                return true;  // keep counting to report the real number of values
            }
            const std::optional<float> v = parse_float(tok);
            if (!v) {
                bad = make_error(source_name, "motion value '" + std::string(tok) + "' is not a number (frame " + std::to_string(f) + ")", number, column);
                return false;
            }
            if (!std::isfinite(*v)) {
                size_t j = 0;
                while (j + 1 < joint_count && first_channel[j + 1] <= n) ++j;
                bad = make_error(source_name, "motion value '" + std::string(tok) + "' is NaN or infinite (frame " + std::to_string(f) + ", joint '" +
                                                  h.skeleton.joints[j].name + "' " + bvh_detail::channel_name(h.channels[j][n - first_channel[j]]) + ")",
                                 number, column);
                return false;
            }
            row[n++] = *v;
            return true;
        });
        if (bad) return *bad;
        if (n != row.size())
            return make_error(source_name, "motion row has " + std::to_string(n) + " values, expected " + std::to_string(row.size()) +
                                               " (frame " + std::to_string(f) + ")", number);
        for (size_t j = 0; j < joint_count; ++j) {
            glm::vec3 t = h.skeleton.joints[j].translation;
            glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);
            const std::vector<Channel>& chans = h.channels[j];
            for (size_t k = 0; k < chans.size(); ++k) {
                const float v = row[first_channel[j] + k];
                if (chans[k] <= Channel::kZposition) t[static_cast<int>(chans[k])] = v * options.unit_scale;
                else q = q * axis_rotation(chans[k], v);
            }
            if (has_pos[j]) raw.tracks[j].translations.values.push_back(t);
            if (has_rot[j]) raw.tracks[j].rotations.values.push_back(glm::normalize(q));
        }
    }

    if (frame_count == 0)  // a skeleton-only file: its clip is one key of the rest pose (the OFFSETs, no rotation)
        for (size_t j = 0; j < joint_count; ++j) {
            if (has_pos[j]) raw.tracks[j].translations.values.push_back(h.skeleton.joints[j].translation);
            if (has_rot[j]) raw.tracks[j].rotations.values.push_back(glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
        }
    std::vector<float> times(std::max<size_t>(frame_count, 1), 0.0f);
    for (size_t f = 0; f < frame_count; ++f) times[f] = static_cast<float>(static_cast<double>(f) * static_cast<double>(*frame_time));
    for (size_t j = 0; j < joint_count; ++j) {
        if (has_pos[j]) raw.tracks[j].translations.times = times;
        if (has_rot[j]) raw.tracks[j].rotations.times = times;
    }
    raw.duration = times.back();

    Result<Skeleton> skeleton = build_skeleton(h.skeleton, source_name);
    if (!skeleton.ok()) return skeleton.error();
    BvhData out;
    out.animation = remap_to_runtime(raw, skeleton.value());
    out.skeleton = std::move(h.skeleton);
    out.frame_time = *frame_time;
    out.frame_count = static_cast<int>(frame_count);
    if (frame_count == 0) out.notes.push_back("the file has no frames (Frames: 0): its clip holds the rest pose");
    return out;
}

Result<BvhData> load_bvh(const std::string& path, const BvhOptions& options) {
    Result<std::string> text = read_text_file(path);
    if (!text.ok()) return text.error();
    return parse_bvh(text.value(), path, options);
}

}  // namespace aloha
