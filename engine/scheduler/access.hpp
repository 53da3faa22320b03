// Typed access for a system: the types it reads (const spans) and writes (mutable spans), declared once
// as template arguments. The scheduler's reads/writes lists are derived from the same types, so the plan
// and the body cannot drift apart: reading an undeclared type, or writing one declared only as read,
// does not compile (tests/engine/scheduler/access_compile_fail.cpp is the suite's proof).
//
// A "source" is anything with `template <class T> std::span<T> span()`: an ECS group, a game's arrays,
// or a host's table of shared state (declare host state as a type too, e.g. `struct CameraState`, and
// hand out a one-element span of it).
#pragma once

#include "engine/ecs/type_id.hpp"
#include "engine/scheduler/system.hpp"

#include <functional>
#include <span>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace aloha {

/// The types a system only reads.
template <class... Ts>
struct Reads {};
/// The types a system writes (and may read).
template <class... Ts>
struct Writes {};

namespace access_detail {
template <class T, class... Ts>
inline constexpr bool contains = (std::is_same_v<T, Ts> || ...);
}  // namespace access_detail

template <class R, class W>
class Access;

/// The spans a system may touch: const spans of its Reads, mutable spans of its Writes.
template <class... R, class... W>
class Access<Reads<R...>, Writes<W...>> {
public:
    /// Takes a span of every declared type from `source` (source.template span<T>()).
    template <class Source>
    explicit Access(Source& source) : reads_(source.template span<R>()...), writes_(source.template span<W>()...) {}

    /// Read-only span of a declared type (read or written).
    template <class T>
    [[nodiscard]] std::span<const T> read() const {
        static_assert(access_detail::contains<T, R..., W...>,
                      "the system reads a type it does not declare: add it to Reads<...> or Writes<...>");
        if constexpr (access_detail::contains<T, W...>)
            return std::get<std::span<T>>(writes_);
        else
            return std::get<std::span<const T>>(reads_);
    }
    /// Mutable span of a type declared in Writes<...>.
    template <class T>
    [[nodiscard]] std::span<T> write() const {
        static_assert(access_detail::contains<T, W...>,
                      "the system writes a type it does not declare as written: add it to Writes<...>");
        return std::get<std::span<T>>(writes_);
    }
    /// The one element of a declared single-object type (host state handed out as a one-element span).
    template <class T>
    [[nodiscard]] const T& one() const {
        return read<T>().front();
    }

    /// The ids the scheduler orders by (SystemDesc::reads / writes).
    [[nodiscard]] static std::vector<ComponentTypeId> read_ids() { return {component_type_id<R>()...}; }
    [[nodiscard]] static std::vector<ComponentTypeId> write_ids() { return {component_type_id<W>()...}; }

private:
    std::tuple<std::span<const R>...> reads_;
    std::tuple<std::span<W>...> writes_;
};

/// A SystemDesc whose reads and writes are A's declared types and whose body gets an A built from
/// `source()` each run: `make_system<Access<Reads<X>, Writes<Y>>>("name", phase, get_source, body)`.
template <class A, class SourceFn, class Body>
SystemDesc make_system(std::string name, Phase phase, SourceFn source, Body body) {
    SystemDesc desc;
    desc.name = std::move(name);
    desc.phase = phase;
    desc.reads = A::read_ids();
    desc.writes = A::write_ids();
    desc.run = [source = std::move(source), body = std::move(body)](SystemContext& ctx) {
        decltype(auto) src = source();  // a reference when the source hands one out
        body(ctx, A(src));
    };
    return desc;
}

}  // namespace aloha
