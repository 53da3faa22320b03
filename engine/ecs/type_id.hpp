// Dense numeric ids for component and resource types (no RTTI) with readable names for messages.
#pragma once

#include <cstdint>
#include <string_view>

namespace aloha {

/// Dense id of a component or resource type; ids are assigned from 0 in first-use order.
using ComponentTypeId = uint32_t;

namespace detail {

/// Registers a new type with `name`; returns its id. Thread-safe.
ComponentTypeId register_type_id(std::string_view name);

/// The compiler's spelling of T, taken from the function signature (GCC/Clang).
template <class T>
constexpr std::string_view pretty_type_name() {
#if defined(__clang__) || defined(__GNUC__)
    constexpr std::string_view full = __PRETTY_FUNCTION__;
    constexpr std::string_view key = "T = ";
    constexpr size_t start = full.find(key) + key.size();
    constexpr size_t end = full.find_first_of(";]", start);
    return full.substr(start, end - start);
#else
    return "unknown type";
#endif
}

}  // namespace detail

/// The id of type T (a component, or any tag type used to name a resource). Same id for the whole
/// process; thread-safe.
template <class T>
ComponentTypeId component_type_id() {
    static const ComponentTypeId id = detail::register_type_id(detail::pretty_type_name<T>());
    return id;
}

/// Alias of component_type_id<Tag>() for resources named by a tag type (e.g. `struct CameraRes {}`).
template <class Tag>
ComponentTypeId resource_type_id() {
    return component_type_id<Tag>();
}

/// The id of a resource named by a string ("camera", "pose pool"); the same name gives the same id.
ComponentTypeId named_type_id(std::string_view name);

/// The readable name of a registered id ("aloha::Transform", "camera"); "<unknown type>" otherwise.
std::string_view type_name(ComponentTypeId id);

/// Number of ids registered so far.
ComponentTypeId type_id_count();

}  // namespace aloha
