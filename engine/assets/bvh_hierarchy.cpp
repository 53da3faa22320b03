#include "engine/assets/bvh_hierarchy.hpp"

#include <cmath>
#include <optional>
#include <set>

namespace aloha::bvh_detail {

namespace {

constexpr const char* kChannelNames[6] = {"Xposition", "Yposition", "Zposition",
                                          "Xrotation", "Yrotation", "Zrotation"};

std::optional<Channel> channel_from_name(std::string_view name) {
    for (int c = 0; c < 6; ++c)
        if (name == kChannelNames[c]) return static_cast<Channel>(c);
    return std::nullopt;
}

// A ROOT / JOINT / End Site whose braces are open (or that waits for its '{').
struct Open {
    int joint = -1;       // raw joint index; -1 for an End Site that is not kept
    bool end_site = false;
    int line = 0;         // line of the declaration
    std::string what;     // "joint 'Hips'" or "End Site of 'LeftToe'"
    bool has_offset = false;
    bool has_channels = false;
};

class HierarchyParser {
public:
    HierarchyParser(const std::string& file, const BvhOptions& options) : file_(file), options_(options) {}

    Result<Hierarchy> run(LineCursor& cursor) {
        std::vector<TextToken> toks;
        std::string_view line;
        int number = 0;
        bool motion = false;
        while (cursor.next(&line, &number)) {
            const size_t before = toks.size();
            tokenize_line(line, number, &toks);
            if (toks.size() > before && toks[before].text == "MOTION") {
                if (toks.size() > before + 1)
                    return err(number, "unexpected '" + std::string(toks[before + 1].text) + "' after MOTION", toks[before + 1].column);
                toks.resize(before);
                out_.motion_line = number;
                motion = true;
                break;
            }
        }
        if (toks.empty()) return err(motion ? out_.motion_line : 1, "expected HIERARCHY at the start of the file");
        if (toks[0].text != "HIERARCHY") return err(toks[0].line, "expected HIERARCHY, found '" + std::string(toks[0].text) + "'", toks[0].column);
        for (size_t i = 1; i < toks.size();) {
            Status s = step(toks, &i);
            if (!s.ok()) return s.error();
        }
        const int end_line = motion ? out_.motion_line : cursor.line_number();
        if (pending_) return err(end_line, "expected '{' after " + pending_->what + " declared at line " + std::to_string(pending_->line));
        if (!stack_.empty()) {
            const Open& top = stack_.back();
            const std::string where = top.what + " opened at line " + std::to_string(top.line);
            if (motion) return err(end_line, "MOTION reached but " + where + " is not closed (unbalanced braces)");
            return err(end_line, "unexpected end of file: " + where + " is not closed (truncated file?)");
        }
        if (out_.skeleton.joints.empty()) return err(end_line, "HIERARCHY has no ROOT joint");
        if (!motion) return err(end_line, "missing MOTION section (file ends at line " + std::to_string(end_line) + ")");
        return std::move(out_);
    }

private:
    Error err(int line, const std::string& message, int column = 0) const { return make_error(file_, message, line, column); }

    // Tokens from toks[*i] onward on the same line as toks[*i - 1]; advances *i past them.
    static std::vector<TextToken> rest_of_line(const std::vector<TextToken>& toks, size_t* i, int line) {
        std::vector<TextToken> out;
        while (*i < toks.size() && toks[*i].line == line) out.push_back(toks[(*i)++]);
        return out;
    }

    Status declare_joint(const TextToken& kw, const std::vector<TextToken>& toks, size_t* i) {
        const bool root = kw.text == "ROOT";
        std::vector<TextToken> name_toks = rest_of_line(toks, i, kw.line);
        if (!name_toks.empty() && name_toks.back().text == "{") {  // "JOINT name {" on one line
            name_toks.pop_back();
            --*i;
        }
        std::string name;
        for (const TextToken& t : name_toks) name += (name.empty() ? "" : " ") + std::string(t.text);
        if (name.empty()) return err(kw.line, std::string(kw.text) + " has no name", kw.column);
        if (root && !stack_.empty())
            return err(kw.line, "ROOT '" + name + "' inside " + stack_.back().what + " opened at line " + std::to_string(stack_.back().line) + " (missing '}'?)");
        if (!root && stack_.empty()) return err(kw.line, "JOINT '" + name + "' outside any ROOT (unbalanced braces?)");
        if (!root && stack_.back().end_site) return err(kw.line, "JOINT '" + name + "' inside an End Site");
        return add_joint(name, root ? -1 : stack_.back().joint, kw.line, false);
    }

    Status add_joint(const std::string& name, int parent, int line, bool end_site) {
        if (out_.skeleton.joints.size() >= 32767) return err(line, "more than 32767 joints");
        if (!names_.insert(name).second) return err(line, "duplicate joint name '" + name + "'");
        RawJoint j;
        j.name = name;
        j.parent = parent;
        out_.skeleton.joints.push_back(j);
        out_.channels.emplace_back();
        Open o;
        o.joint = static_cast<int>(out_.skeleton.joints.size()) - 1;
        o.end_site = end_site;
        o.line = line;
        o.what = end_site ? "End Site '" + name + "'" : "joint '" + name + "'";
        pending_ = o;
        return {};
    }

    Status offset(const TextToken& kw, const std::vector<TextToken>& toks, size_t* i) {
        if (stack_.empty()) return err(kw.line, "OFFSET outside any joint", kw.column);
        Open& top = stack_.back();
        if (top.has_offset) return err(kw.line, "second OFFSET in " + top.what, kw.column);
        const std::vector<TextToken> nums = rest_of_line(toks, i, kw.line);
        if (nums.size() != 3) return err(kw.line, "OFFSET needs 3 numbers, found " + std::to_string(nums.size()), kw.column);
        glm::vec3 v(0.0f);
        for (int a = 0; a < 3; ++a) {
            const TextToken& t = nums[static_cast<size_t>(a)];
            const std::optional<float> f = parse_float(t.text);
            if (!f) return err(t.line, "OFFSET value '" + std::string(t.text) + "' is not a number", t.column);
            if (!std::isfinite(*f)) return err(t.line, "OFFSET value '" + std::string(t.text) + "' is NaN or infinite", t.column);
            v[a] = *f * options_.unit_scale;
        }
        top.has_offset = true;
        if (top.joint >= 0) out_.skeleton.joints[static_cast<size_t>(top.joint)].translation = v;
        return {};
    }

    Status channels(const TextToken& kw, const std::vector<TextToken>& toks, size_t* i) {
        if (stack_.empty()) return err(kw.line, "CHANNELS outside any joint", kw.column);
        Open& top = stack_.back();
        if (top.end_site) return err(kw.line, "CHANNELS in an End Site", kw.column);
        if (top.has_channels) return err(kw.line, "second CHANNELS in " + top.what, kw.column);
        const std::vector<TextToken> rest = rest_of_line(toks, i, kw.line);
        if (rest.empty()) return err(kw.line, "CHANNELS needs a count", kw.column);
        const std::optional<int64_t> n = parse_int(rest[0].text);
        if (!n || *n < 0 || *n > 6)
            return err(kw.line, "CHANNELS count '" + std::string(rest[0].text) + "' is not a number from 0 to 6", rest[0].column);
        if (rest.size() - 1 != static_cast<size_t>(*n))
            return err(kw.line, "CHANNELS declares " + std::to_string(*n) + " channels but lists " + std::to_string(rest.size() - 1), kw.column);
        std::vector<Channel>& list = out_.channels[static_cast<size_t>(top.joint)];
        for (size_t k = 1; k < rest.size(); ++k) {
            const std::optional<Channel> c = channel_from_name(rest[k].text);
            if (!c)
                return err(kw.line, "unknown channel name '" + std::string(rest[k].text) +
                                        "' (expected Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation)", rest[k].column);
            for (Channel seen : list)
                if (seen == *c) return err(kw.line, "channel '" + std::string(rest[k].text) + "' listed twice", rest[k].column);
            list.push_back(*c);
        }
        out_.total_channels += list.size();
        top.has_channels = true;
        return {};
    }

    Status step(const std::vector<TextToken>& toks, size_t* i) {
        const TextToken& t = toks[(*i)++];
        if (pending_ && t.text != "{")
            return err(t.line, "expected '{' after " + pending_->what + " declared at line " + std::to_string(pending_->line) + ", found '" + std::string(t.text) + "'", t.column);
        if (t.text == "ROOT" || t.text == "JOINT") return declare_joint(t, toks, i);
        if (t.text == "End") {
            if (*i >= toks.size() || toks[*i].line != t.line || toks[*i].text != "Site") return err(t.line, "expected 'End Site'", t.column);
            ++*i;
            if (stack_.empty() || stack_.back().end_site) return err(t.line, "End Site outside a joint", t.column);
            const int parent = stack_.back().joint;
            const std::string& parent_name = out_.skeleton.joints[static_cast<size_t>(parent)].name;
            if (options_.keep_end_sites) return add_joint(parent_name + "_End", parent, t.line, true);
            Open o;
            o.end_site = true;
            o.line = t.line;
            o.what = "End Site of '" + parent_name + "'";
            pending_ = o;
            return {};
        }
        if (t.text == "{") {
            if (!pending_) return err(t.line, "unexpected '{'", t.column);
            stack_.push_back(*pending_);
            pending_.reset();
            return {};
        }
        if (t.text == "}") {
            if (stack_.empty()) return err(t.line, "unbalanced '}': no joint is open", t.column);
            const Open& top = stack_.back();
            if (!top.has_offset) return err(t.line, top.what + " (line " + std::to_string(top.line) + ") has no OFFSET");
            if (!top.end_site && !top.has_channels) return err(t.line, top.what + " (line " + std::to_string(top.line) + ") has no CHANNELS");
            stack_.pop_back();
            return {};
        }
        if (t.text == "OFFSET") return offset(t, toks, i);
        if (t.text == "CHANNELS") return channels(t, toks, i);
        return err(t.line, "unexpected '" + std::string(t.text) + "' in HIERARCHY", t.column);
    }

    const std::string& file_;
    const BvhOptions& options_;
    Hierarchy out_;
    std::vector<Open> stack_;
    std::optional<Open> pending_;
    std::set<std::string> names_;
};

}  // namespace

const char* channel_name(Channel c) { return kChannelNames[static_cast<int>(c)]; }

Result<Hierarchy> parse_hierarchy(LineCursor& cursor, const std::string& file, const BvhOptions& options) {
    HierarchyParser parser(file, options);
    return parser.run(cursor);
}

}  // namespace aloha::bvh_detail
