#include "engine/ecs/command_buffer.hpp"

namespace aloha {

Entity CommandBuffer::spawn() {
    const Entity pending{pending_count_++, kPendingGeneration};
    commands_.push_back(Command{Kind::Spawn, pending, 0, 0});
    return pending;
}

void CommandBuffer::despawn(Entity e) { commands_.push_back(Command{Kind::Despawn, e, 0, 0}); }

size_t CommandBuffer::apply(Registry& registry) {
    spawned_.clear();
    spawned_.reserve(pending_count_);
    size_t skipped = 0;
    for (const Command& c : commands_) {
        if (c.kind == Kind::Spawn) {
            spawned_.push_back(registry.create());
            continue;
        }
        Entity target = c.target;
        if (is_pending(target)) {
            target = target.index < spawned_.size() ? spawned_[target.index] : kNullEntity;
        }
        if (!registry.valid(target)) {
            ++skipped;
            continue;
        }
        switch (c.kind) {
            case Kind::Despawn:
                registry.destroy(target);
                break;
            case Kind::Add:
                payloads_[c.type]->emplace(registry, target, c.payload);
                break;
            case Kind::Remove:
                if (StorageBase* s = registry.storage_by_id(c.type)) s->remove(target);
                break;
            case Kind::Spawn:
                break;
        }
    }
    commands_.clear();
    for (const auto& p : payloads_) {
        if (p) p->clear();
    }
    pending_count_ = 0;
    return skipped;
}

void CommandBuffer::clear() {
    commands_.clear();
    for (const auto& p : payloads_) {
        if (p) p->clear();
    }
    pending_count_ = 0;
}

}  // namespace aloha
