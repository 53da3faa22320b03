// Per-level character storage of the geometric controller: one fixed-size record per slot, handed
// out from a free list. Records live in pages of a power-of-two number of slots that are never moved
// or freed while the store lives: growing adds a page (no copy, spans stay valid), released slots are
// reused (last released first), so enter/leave cycles keep memory flat. When the free slots run low a
// spare page is allocated and its memory touched on a lower-priority background thread, so the level
// switch that needs it does not stall on page faults (issue 18: no hitch at a switch).
#pragma once

#include "components/transform.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <future>
#include <memory>
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

/// Storage for one level's characters. Not thread-safe for acquire/release/reserve; the per-slot spans
/// of distinct slots may be written concurrently. A newly acquired slot's buffers hold unspecified
/// values (its users write before they read); its flags are cleared.
class SlotStore {
public:
    /// A store with no slots for records shaped by `layout`.
    explicit SlotStore(const SlotLayout& layout);
    ~SlotStore();
    SlotStore(const SlotStore&) = delete;
    SlotStore& operator=(const SlotStore&) = delete;

    /// A free slot (the most recently released one first), adding a page when none is free (the
    /// background spare if one was started). Spans returned before stay valid.
    uint32_t acquire();
    /// Makes room for at least `slots` slots in all (no-op when there is room), touching the new pages'
    /// memory now: lets a caller that knows how many characters will enter pay for them up front.
    void reserve(uint32_t slots);
    /// Returns `slot` to the free list. Requires it to be in use.
    void release(uint32_t slot);
    /// Slots allocated (in use + free); a multiple of slots_per_page().
    [[nodiscard]] uint32_t capacity() const { return capacity_; }
    /// Slots in use.
    [[nodiscard]] uint32_t in_use() const { return capacity_ - static_cast<uint32_t>(free_.size()); }
    /// Slots of one page (a power of two, at least one, chosen so a page holds about 1 MiB).
    [[nodiscard]] uint32_t slots_per_page() const { return 1u << page_shift_; }
    /// Bytes held by pages not yet part of the capacity (the background spare, once started).
    [[nodiscard]] size_t spare_bytes() const { return spare_.valid() ? page_bytes() : 0; }
    /// The record shape.
    [[nodiscard]] const SlotLayout& layout() const { return layout_; }
    /// Bytes of one slot's buffers and flags (what one character costs, without the record's padding).
    [[nodiscard]] size_t bytes_per_slot() const;
    /// Bytes allocated: every page (padding included), the flags and the spare.
    [[nodiscard]] size_t allocated_bytes() const;

    /// Per-slot buffers (spans of the layout's sizes). Require slot < capacity().
    std::span<glm::mat4> boxes(uint32_t s) { return part<glm::mat4>(kBoxes, s); }
    std::span<glm::mat4> palette(uint32_t s) { return part<glm::mat4>(kPalette, s); }
    std::span<glm::vec3> centres(uint32_t s) { return part<glm::vec3>(kCentres, s); }
    std::span<glm::quat> rotations(uint32_t s) { return part<glm::quat>(kRotations, s); }
    std::span<glm::vec3> radii(uint32_t s) { return part<glm::vec3>(kRadii, s); }
    std::span<glm::vec3> muscle_positions(uint32_t s) { return part<glm::vec3>(kMusclePos, s); }
    std::span<glm::vec3> muscle_normals(uint32_t s) { return part<glm::vec3>(kMuscleNrm, s); }
    std::span<glm::vec3> spring_end(uint32_t s) { return part<glm::vec3>(kSpringEnd, s); }
    std::span<glm::vec3> spring_velocity(uint32_t s) { return part<glm::vec3>(kSpringVel, s); }
    std::span<glm::vec3> spring_prev_rest(uint32_t s) { return part<glm::vec3>(kSpringPrev, s); }
    std::span<uint8_t> spring_initialised(uint32_t s) { return part<uint8_t>(kSpringInit, s); }
    std::span<glm::vec3> positions(uint32_t s) { return part<glm::vec3>(kPositions, s); }
    std::span<glm::vec3> deltas(uint32_t s) { return part<glm::vec3>(kDeltas, s); }
    std::span<glm::vec3> normals(uint32_t s) { return part<glm::vec3>(kNormals, s); }
    std::span<glm::vec3> refined_positions(uint32_t s) { return part<glm::vec3>(kRefinedPos, s); }
    std::span<glm::vec3> refined_normals(uint32_t s) { return part<glm::vec3>(kRefinedNrm, s); }
    /// Morph counters of one slot as one-element spans (GeomorphJob's per-character layout).
    std::span<uint16_t> frames_total(uint32_t s) { return std::span(frames_total_).subspan(s, 1); }
    std::span<uint16_t> frames_left(uint32_t s) { return std::span(frames_left_).subspan(s, 1); }
    /// Morph frames still to show in slot `s`.
    [[nodiscard]] uint16_t frames_left_of(uint32_t s) const { return frames_left_[s]; }

    /// Read-only views of the same buffers.
    [[nodiscard]] std::span<const glm::mat4> boxes(uint32_t s) const { return cpart<glm::mat4>(kBoxes, s); }
    [[nodiscard]] std::span<const glm::vec3> muscle_positions(uint32_t s) const { return cpart<glm::vec3>(kMusclePos, s); }
    [[nodiscard]] std::span<const glm::vec3> muscle_normals(uint32_t s) const { return cpart<glm::vec3>(kMuscleNrm, s); }
    [[nodiscard]] std::span<const glm::vec3> spring_end(uint32_t s) const { return cpart<glm::vec3>(kSpringEnd, s); }
    [[nodiscard]] std::span<const glm::vec3> positions(uint32_t s) const { return cpart<glm::vec3>(kPositions, s); }
    [[nodiscard]] std::span<const glm::vec3> normals(uint32_t s) const { return cpart<glm::vec3>(kNormals, s); }
    [[nodiscard]] std::span<const glm::vec3> refined_positions(uint32_t s) const { return cpart<glm::vec3>(kRefinedPos, s); }
    [[nodiscard]] std::span<const glm::vec3> refined_normals(uint32_t s) const { return cpart<glm::vec3>(kRefinedNrm, s); }

    /// Per-slot flags: a morph's start is still to be read (the first update fills deltas), the displayed control
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
    enum Buffer : uint8_t {
        kBoxes, kPalette, kCentres, kRotations, kRadii, kMusclePos, kMuscleNrm, kSpringEnd, kSpringVel,
        kSpringPrev, kSpringInit, kPositions, kDeltas, kNormals, kRefinedPos, kRefinedNrm, kBufferCount
    };
    using Page = std::unique_ptr<std::byte[]>;

    [[nodiscard]] std::byte* record(uint32_t s) const {
        return pages_[s >> page_shift_].get() + size_t{s & ((1u << page_shift_) - 1)} * record_bytes_;
    }
    template <class T>
    std::span<T> part(Buffer b, uint32_t s) {
        assert(s < capacity_);
        return {reinterpret_cast<T*>(record(s) + offset_[b]), count_[b]};
    }
    template <class T>
    [[nodiscard]] std::span<const T> cpart(Buffer b, uint32_t s) const {
        assert(s < capacity_);
        return {reinterpret_cast<const T*>(record(s) + offset_[b]), count_[b]};
    }
    [[nodiscard]] size_t page_bytes() const { return size_t{record_bytes_} << page_shift_; }
    [[nodiscard]] size_t flag_bytes() const;  ///< one slot's flags and counters (kept outside the pages)
    void add_page(Page page);
    void start_spare();

    SlotLayout layout_;
    std::array<size_t, kBufferCount> offset_{};  ///< byte offset of each buffer in a record
    std::array<size_t, kBufferCount> count_{};   ///< elements of each buffer per record
    std::array<size_t, kBufferCount> element_bytes_{};  ///< bytes of one element of each buffer
    size_t record_bytes_ = 0;                     ///< one record, a multiple of 64 bytes
    uint32_t page_shift_ = 0;                     ///< log2 of the slots per page
    uint32_t capacity_ = 0;
    std::vector<uint32_t> free_;
    std::vector<Page> pages_;
    std::future<Page> spare_;  ///< a page being allocated and touched in the background (or none)
    std::vector<uint16_t> frames_total_, frames_left_;
};

}  // namespace aloha
