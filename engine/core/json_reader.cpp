#include "engine/core/json_reader.hpp"

#include "engine/core/json_depth.hpp"
#include "engine/core/text_position.hpp"

#include <cmath>

namespace aloha {

namespace {
const char* type_name(const nlohmann::json& v) { return v.type_name(); }

std::string range_text(double lo, double hi) { return "[" + json_number_text(lo) + ", " + json_number_text(hi) + "]"; }
}  // namespace

std::string json_number_text(double value) { return nlohmann::json(value).dump(); }

JsonObjectReader::JsonObjectReader(const nlohmann::json& value, std::string path, const std::string& file,
                                   std::vector<Error>& errors)
    : path_(std::move(path)), file_(file), errors_(errors) {
    if (value.is_object()) object_ = &value;
    else errors_.push_back(make_error(file_, std::string("expected an object, got ") + type_name(value), 0, 0,
                                      path_.empty() ? "/" : path_));
}

void JsonObjectReader::error(const std::string& sub_path, const std::string& message) { error_at(0, 0, sub_path, message); }

void JsonObjectReader::error_at(int line, int column, const std::string& sub_path, const std::string& message) {
    std::string p = path_;
    if (!sub_path.empty()) p += "/" + sub_path;
    errors_.push_back(make_error(file_, message, line, column, p.empty() ? "/" : p));
}

bool JsonObjectReader::has(const char* key) {
    allow({key});
    return object_ && object_->contains(key);
}

void JsonObjectReader::allow(std::initializer_list<const char*> keys) {
    for (const char* k : keys)
        if (known_.insert(k).second) known_order_.push_back(k);
}

const nlohmann::json* JsonObjectReader::child(const char* key) {
    allow({key});
    if (!object_) return nullptr;
    auto it = object_->find(key);
    return it == object_->end() ? nullptr : &*it;
}

double JsonObjectReader::number(const char* key, double fallback, double lo, double hi, bool required) {
    const nlohmann::json* v = child(key);
    if (!v) {
        if (required && object_) error("", std::string("missing required key '") + key + "'");
        return fallback;
    }
    if (!v->is_number()) {
        error(key, std::string("expected a number, got ") + type_name(*v));
        return fallback;
    }
    const double d = v->get<double>();
    if (!std::isfinite(d)) {
        error(key, "number is not finite");
        return fallback;
    }
    if (d < lo || d > hi) {
        error(key, "value " + v->dump() + " is out of range " + range_text(lo, hi));
        return fallback;
    }
    return d;
}

int64_t JsonObjectReader::integer(const char* key, int64_t fallback, int64_t lo, int64_t hi, bool required) {
    const nlohmann::json* v = child(key);
    if (!v) {
        if (required && object_) error("", std::string("missing required key '") + key + "'");
        return fallback;
    }
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (v->is_number_float()) {
        const double d = v->get<double>();
        if (!std::isfinite(d) || d != std::floor(d)) {
            error(key, "expected an integer, got " + v->dump());
            return fallback;
        }
        if (d < static_cast<double>(lo) || d > static_cast<double>(hi)) {
            error(key, "value " + v->dump() + " is out of range " + range);
            return fallback;
        }
        return static_cast<int64_t>(d);
    }
    if (!v->is_number_integer()) {
        error(key, std::string("expected an integer, got ") + type_name(*v));
        return fallback;
    }
    // Unsigned values beyond int64 range are rejected as out of range.
    if ((v->is_number_unsigned() && v->get<uint64_t>() > static_cast<uint64_t>(hi)) || v->get<int64_t>() < lo ||
        v->get<int64_t>() > hi) {
        error(key, "value " + v->dump() + " is out of range " + range);
        return fallback;
    }
    return v->get<int64_t>();
}

bool JsonObjectReader::boolean(const char* key, bool fallback) {
    const nlohmann::json* v = child(key);
    if (!v) return fallback;
    if (!v->is_boolean()) {
        error(key, std::string("expected true or false, got ") + type_name(*v));
        return fallback;
    }
    return v->get<bool>();
}

std::string JsonObjectReader::string(const char* key, const std::string& fallback, bool required) {
    const nlohmann::json* v = child(key);
    if (!v) {
        if (required && object_) error("", std::string("missing required key '") + key + "'");
        return fallback;
    }
    if (!v->is_string()) {
        error(key, std::string("expected a string, got ") + type_name(*v));
        return fallback;
    }
    std::string s = v->get<std::string>();
    if (required && s.empty()) error(key, "expected a non-empty string");
    return s;
}

int JsonObjectReader::choice(const char* key, std::initializer_list<const char*> names, int fallback, bool required) {
    const nlohmann::json* v = child(key);
    if (!v) {
        if (required && object_) error("", std::string("missing required key '") + key + "'");
        return fallback;
    }
    std::string list;
    int i = 0;
    for (const char* n : names) {
        if (v->is_string() && v->get<std::string>() == n) return i;
        list += std::string(list.empty() ? "" : ", ") + n;
        ++i;
    }
    error(key, "unknown value " + v->dump() + " (allowed: " + list + ")");
    return fallback;
}

void JsonObjectReader::renamed(const char* old_key, const char* new_key, const std::string& why) {
    if (has(old_key)) error(old_key, std::string("'") + old_key + "' was replaced by '" + new_key + "'" + (why.empty() ? "" : " (" + why + ")"));
}

glm::vec3 read_vec3(const nlohmann::json& value, const std::string& path, const std::string& file,
                    std::vector<Error>& errors, const glm::vec3& fallback, double bound) {
    if (!value.is_array() || value.size() != 3) {
        errors.push_back(make_error(file, "expected [x, y, z], got " + value.dump().substr(0, 40), 0, 0, path));
        return fallback;
    }
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const auto& c = value[static_cast<size_t>(i)];
        if (!c.is_number() || !std::isfinite(c.get<double>()) || std::abs(c.get<double>()) > bound) {
            errors.push_back(make_error(file, "expected a finite number within " + range_text(-bound, bound) + ", got " + c.dump(),
                                        0, 0, path + "/" + std::to_string(i)));
            return fallback;
        }
        out[i] = c.get<float>();
    }
    return out;
}

glm::vec3 JsonObjectReader::vec3(const char* key, const glm::vec3& fallback, bool required, double bound) {
    const nlohmann::json* v = child(key);
    if (!v) {
        if (required && object_) error("", std::string("missing required key '") + key + "'");
        return fallback;
    }
    return read_vec3(*v, child_path(key), file_, errors_, fallback, bound);
}

void JsonObjectReader::reject_unknown_keys() {
    if (!object_) return;
    std::string allowed;
    for (const std::string& k : known_order_) allowed += (allowed.empty() ? "" : ", ") + k;
    for (auto it = object_->begin(); it != object_->end(); ++it)
        if (!known_.count(it.key()))
            error(it.key(), "unknown key '" + it.key() + "'" + (allowed.empty() ? std::string() : " (allowed: " + allowed + ")"));
}

Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file, bool allow_comments) {
    if (Status deep = check_json_depth(text, file); !deep.ok()) return deep.error();
    nlohmann::json j = nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false, allow_comments);
    if (!j.is_discarded()) return j;
    // Re-parse with exceptions to get the byte position of the syntax error.
    int line = 0, column = 0;
    try {
        const nlohmann::json again = nlohmann::json::parse(text.begin(), text.end(), nullptr, true, allow_comments);
        (void)again;
    } catch (const nlohmann::json::parse_error& e) {
        line_column_of(text, e.byte == 0 ? 0 : e.byte - 1, &line, &column);  // e.byte: 1-based
        std::string what = e.what();
        const auto pos = what.find("syntax error");
        return make_error(file, "invalid JSON: " + (pos == std::string::npos ? what : what.substr(pos)), line, column);
    } catch (const nlohmann::json::out_of_range& e) {
        // e.g. "number overflow parsing '1e999'": place it at the first occurrence of the literal.
        std::string what = e.what();
        const auto open = what.find('\''), close = what.rfind('\'');
        if (open != std::string::npos && close > open + 1) {
            const size_t at = text.find(what.substr(open + 1, close - open - 1));
            if (at != std::string::npos) line_column_of(text, at, &line, &column);
        }
        const auto pos = what.find("number overflow");
        return make_error(file, "invalid JSON: " + (pos == std::string::npos ? what : what.substr(pos)), line, column);
    } catch (const std::exception& e) {
        return make_error(file, std::string("invalid JSON: ") + e.what());
    }
    return make_error(file, "invalid JSON");
}

}  // namespace aloha
