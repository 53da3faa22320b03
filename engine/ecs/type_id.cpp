#include "engine/ecs/type_id.hpp"

#include <deque>
#include <map>
#include <mutex>
#include <string>

namespace aloha {
namespace {

struct TypeTable {
    std::mutex mutex;
    std::deque<std::string> names;  // deque: references stay valid as it grows
    std::map<std::string, ComponentTypeId, std::less<>> by_name;  // named resources only
};

TypeTable& table() {
    static TypeTable t;
    return t;
}

}  // namespace

namespace detail {

ComponentTypeId register_type_id(std::string_view name) {
    TypeTable& t = table();
    const std::lock_guard<std::mutex> lock(t.mutex);
    t.names.emplace_back(name);
    return static_cast<ComponentTypeId>(t.names.size() - 1);
}

}  // namespace detail

ComponentTypeId named_type_id(std::string_view name) {
    TypeTable& t = table();
    const std::lock_guard<std::mutex> lock(t.mutex);
    if (auto it = t.by_name.find(name); it != t.by_name.end()) return it->second;
    t.names.emplace_back(name);
    const auto id = static_cast<ComponentTypeId>(t.names.size() - 1);
    t.by_name.emplace(std::string(name), id);
    return id;
}

std::string_view type_name(ComponentTypeId id) {
    TypeTable& t = table();
    const std::lock_guard<std::mutex> lock(t.mutex);
    if (id < t.names.size()) return t.names[id];
    return "<unknown type>";
}

ComponentTypeId type_id_count() {
    TypeTable& t = table();
    const std::lock_guard<std::mutex> lock(t.mutex);
    return static_cast<ComponentTypeId>(t.names.size());
}

}  // namespace aloha
