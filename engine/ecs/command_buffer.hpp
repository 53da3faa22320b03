// CommandBuffer: structural changes (spawn, despawn, add, remove) recorded while systems iterate
// and applied to a Registry between phases, in recording order.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "engine/ecs/registry.hpp"

namespace aloha {

/// Records structural changes for later. Recording never touches the registry, so it is safe in
/// the middle of a view or group iteration. One buffer must not be recorded from two threads at
/// once (give each system or thread its own buffer and apply them in a fixed order).
class CommandBuffer {
public:
    /// Generation marking a handle returned by spawn() that is not yet a real entity.
    static constexpr uint32_t kPendingGeneration = UINT32_MAX - 1;

    /// Records the creation of an entity; the returned pending handle may be used in later
    /// commands of this buffer (it is resolved at apply time). It is not valid in any registry.
    Entity spawn();
    /// Records the destruction of `e` (a live or pending handle).
    void despawn(Entity e);
    /// Records giving `e` a component `value` (replacing an existing one).
    template <class T>
    void add(Entity e, T value) {
        const ComponentTypeId id = component_type_id<T>();
        if (id >= payloads_.size()) payloads_.resize(id + 1);
        if (!payloads_[id]) payloads_[id] = std::make_unique<Payload<T>>();
        auto& pool = static_cast<Payload<T>&>(*payloads_[id]);
        commands_.push_back(Command{Kind::Add, e, id, static_cast<uint32_t>(pool.values.size())});
        pool.values.push_back(std::move(value));
    }
    /// Records removing `e`'s component T.
    template <class T>
    void remove(Entity e) {
        commands_.push_back(Command{Kind::Remove, e, component_type_id<T>(), 0});
    }

    /// Applies every command in recording order and empties the buffer (keeping its memory).
    /// Commands whose target is dead (destroyed earlier, stale, or a foreign pending handle) are
    /// skipped; returns how many were skipped.
    size_t apply(Registry& registry);
    /// The real entities created by the last apply(), in spawn() order (pending index i -> [i]).
    [[nodiscard]] std::span<const Entity> spawned() const { return spawned_; }
    /// Number of recorded commands.
    [[nodiscard]] size_t size() const { return commands_.size(); }
    /// True when nothing is recorded.
    [[nodiscard]] bool empty() const { return commands_.empty(); }
    /// Drops every recorded command.
    void clear();
    /// True when `e` is a pending handle returned by spawn().
    [[nodiscard]] static bool is_pending(Entity e) { return e.generation == kPendingGeneration; }

private:
    enum class Kind : uint8_t { Spawn, Despawn, Add, Remove };
    struct Command {
        Kind kind;
        Entity target;
        ComponentTypeId type;
        uint32_t payload;  // index into the type's payload pool (Add only)
    };
    struct PayloadBase {
        virtual ~PayloadBase() = default;
        virtual void emplace(Registry& registry, Entity e, uint32_t index) = 0;
        virtual void clear() = 0;
    };
    template <class T>
    struct Payload final : PayloadBase {
        std::vector<T> values;
        void emplace(Registry& registry, Entity e, uint32_t index) override {
            registry.emplace<T>(e, std::move(values[index]));
        }
        void clear() override { values.clear(); }
    };

    std::vector<Command> commands_;
    std::vector<std::unique_ptr<PayloadBase>> payloads_;  // indexed by ComponentTypeId
    std::vector<Entity> spawned_;
    uint32_t pending_count_ = 0;
};

}  // namespace aloha
