// Per-level character storage of the geometric controller: one fixed-size record per slot, laid
// out structure-of-arrays (each buffer holds capacity x per-slot elements), handed out from a
// free list. Capacity grows (doubling) only when every slot is taken; released slots are reused
// (last released first), so enter/leave cycles keep memory flat.
#pragma once

#include "components/transform.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Elements per slot of every buffer a level needs (0 = buffer unused by the level).
struct SlotLayout {
    uint32_t boxes = 0;             ///< proxy boxes (joints) for RigidProxy
    uint32_t palette = 0;           ///< skinning palette (joints) for SkinnedMesh
    uint32_t shapes = 0;            ///< muscle centres / rotations / radii (muscles)
    uint32_t muscle_vertices = 0;   ///< tessellated muscle positions / normals (muscle -> spring_skin)
    uint32_t springs = 0;           ///< fat-spring end / velocity / previous rest (grid skin)
    uint32_t spring_flags = 0;      ///< fat-spring "initialised" flags (muscles)
    uint32_t control = 0;           ///< displayed control surface positions
    uint32_t morph = 0;             ///< geomorph offsets: one per displayed vertex (0 = the level does not morph)
    uint32_t control_normals = 0;   ///< normals of the control surface (0 when it is subdivided)
    uint32_t refined = 0;           ///< subdivided positions / normals
};

/// Storage for one level's characters. Not thread-safe for acquire/release; the per-slot spans of
/// distinct slots may be written concurrently.
class SlotStore {
public:
    /// A store with no slots for records shaped by `layout`.
    explicit SlotStore(const SlotLayout& layout) : layout_(layout) {}

    /// A free slot (the most recently released one first), growing the buffers when none is free.
    /// Growing invalidates previously returned spans.
    uint32_t acquire();
    /// Makes room for `slots` slots in all (no-op when there is room): lets a caller that knows how
    /// many characters will enter allocate once instead of doubling (which briefly holds both).
    void reserve(uint32_t slots);
    /// Returns `slot` to the free list. Requires it to be in use.
    void release(uint32_t slot);
    /// Slots allocated (in use + free).
    [[nodiscard]] uint32_t capacity() const { return capacity_; }
    /// Slots in use.
    [[nodiscard]] uint32_t in_use() const { return capacity_ - static_cast<uint32_t>(free_.size()); }
    /// The record shape.
    [[nodiscard]] const SlotLayout& layout() const { return layout_; }
    /// Bytes of one slot's record.
    [[nodiscard]] size_t bytes_per_slot() const;

    /// Per-slot buffers (spans of the layout's sizes). Require slot < capacity().
    std::span<glm::mat4> boxes(uint32_t s) { return part(boxes_, layout_.boxes, s); }
    std::span<glm::mat4> palette(uint32_t s) { return part(palette_, layout_.palette, s); }
    std::span<glm::vec3> centres(uint32_t s) { return part(centres_, layout_.shapes, s); }
    std::span<glm::quat> rotations(uint32_t s) { return part(rotations_, layout_.shapes, s); }
    std::span<glm::vec3> radii(uint32_t s) { return part(radii_, layout_.shapes, s); }
    std::span<glm::vec3> muscle_positions(uint32_t s) { return part(muscle_pos_, layout_.muscle_vertices, s); }
    std::span<glm::vec3> muscle_normals(uint32_t s) { return part(muscle_nrm_, layout_.muscle_vertices, s); }
    std::span<glm::vec3> spring_end(uint32_t s) { return part(spring_end_, layout_.springs, s); }
    std::span<glm::vec3> spring_velocity(uint32_t s) { return part(spring_vel_, layout_.springs, s); }
    std::span<glm::vec3> spring_prev_rest(uint32_t s) { return part(spring_prev_, layout_.springs, s); }
    std::span<uint8_t> spring_initialised(uint32_t s) { return part(spring_init_, layout_.spring_flags, s); }
    std::span<glm::vec3> positions(uint32_t s) { return part(positions_, layout_.control, s); }
    std::span<glm::vec3> deltas(uint32_t s) { return part(deltas_, layout_.morph, s); }
    std::span<glm::vec3> normals(uint32_t s) { return part(normals_, layout_.control_normals, s); }
    std::span<glm::vec3> refined_positions(uint32_t s) { return part(refined_pos_, layout_.refined, s); }
    std::span<glm::vec3> refined_normals(uint32_t s) { return part(refined_nrm_, layout_.refined, s); }
    /// Morph counters of one slot as one-element spans (GeomorphJob's per-character layout).
    std::span<uint16_t> frames_total(uint32_t s) { return std::span(frames_total_).subspan(s, 1); }
    std::span<uint16_t> frames_left(uint32_t s) { return std::span(frames_left_).subspan(s, 1); }
    /// Morph frames still to show in slot `s`.
    [[nodiscard]] uint16_t frames_left_of(uint32_t s) const { return frames_left_[s]; }

    /// Read-only views of the same buffers.
    [[nodiscard]] std::span<const glm::mat4> boxes(uint32_t s) const { return cpart(boxes_, layout_.boxes, s); }
    [[nodiscard]] std::span<const glm::vec3> muscle_positions(uint32_t s) const { return cpart(muscle_pos_, layout_.muscle_vertices, s); }
    [[nodiscard]] std::span<const glm::vec3> muscle_normals(uint32_t s) const { return cpart(muscle_nrm_, layout_.muscle_vertices, s); }
    [[nodiscard]] std::span<const glm::vec3> spring_end(uint32_t s) const { return cpart(spring_end_, layout_.springs, s); }
    [[nodiscard]] std::span<const glm::vec3> positions(uint32_t s) const { return cpart(positions_, layout_.control, s); }
    [[nodiscard]] std::span<const glm::vec3> normals(uint32_t s) const { return cpart(normals_, layout_.control_normals, s); }
    [[nodiscard]] std::span<const glm::vec3> refined_positions(uint32_t s) const { return cpart(refined_pos_, layout_.refined, s); }
    [[nodiscard]] std::span<const glm::vec3> refined_normals(uint32_t s) const { return cpart(refined_nrm_, layout_.refined, s); }

    /// Per-slot flags: a morph start is pending (deltas hold the old surface), the displayed control
    /// surface is `positions` (morph shown) rather than the spring ends, the slot has been updated.
    std::vector<uint8_t> pending;
    std::vector<uint8_t> shows_morph;
    std::vector<uint8_t> valid;
    /// Per slot of a level with fat springs (empty otherwise): the character's world placement when its
    /// springs last stepped, and whether it is known (fat_spring_frame.hpp carries the springs from it
    /// to this frame's placement).
    std::vector<Transform> placement;
    std::vector<uint8_t> placed;

private:
    template <class T>
    static std::span<T> part(std::vector<T>& v, uint32_t per, uint32_t s) {
        return std::span(v).subspan(size_t{s} * per, per);
    }
    template <class T>
    static std::span<const T> cpart(const std::vector<T>& v, uint32_t per, uint32_t s) {
        return std::span(v).subspan(size_t{s} * per, per);
    }
    void grow(uint32_t new_capacity);

    SlotLayout layout_;
    uint32_t capacity_ = 0;
    std::vector<uint32_t> free_;
    std::vector<glm::mat4> boxes_, palette_;
    std::vector<glm::vec3> centres_, radii_;
    std::vector<glm::quat> rotations_;
    std::vector<glm::vec3> muscle_pos_, muscle_nrm_, spring_end_, spring_vel_, spring_prev_;
    std::vector<uint8_t> spring_init_;
    std::vector<glm::vec3> positions_, deltas_, normals_, refined_pos_, refined_nrm_;
    std::vector<uint16_t> frames_total_, frames_left_;
};

}  // namespace aloha
