#include "systems/lod/rule_set.hpp"

#include <system_error>

namespace aloha {

Status RuleSet::load(const std::string& path) {
    path_ = path;
    return reload_from_file();
}

Status RuleSet::reload_from_file() {
    std::error_code ec;
    const auto stamp = std::filesystem::last_write_time(path_, ec);
    if (!ec) stamp_ = stamp;
    const auto size = std::filesystem::file_size(path_, ec);
    if (!ec) size_ = size;
    last_errors_.clear();
    Result<RuleTable> r = load_rules(path_, &last_errors_);
    if (!r.ok()) return r.error();
    last_errors_.clear();
    set_table(std::move(r).value());
    return {};
}

Result<bool> RuleSet::poll() {
    std::error_code ec;
    const auto stamp = std::filesystem::last_write_time(path_, ec);
    if (ec) return make_error(path_, "cannot read the rule file's modification time: " + ec.message());
    const auto size = std::filesystem::file_size(path_, ec);
    if (ec) return make_error(path_, "cannot read the rule file's size: " + ec.message());
    if (stamp == stamp_ && size == size_) return false;
    Status s = reload_from_file();
    if (!s.ok()) return s.error();
    return true;
}

void RuleSet::set_table(RuleTable table) {
    table_ = std::make_shared<const RuleTable>(std::move(table));
    ++generation_;
}

}  // namespace aloha
