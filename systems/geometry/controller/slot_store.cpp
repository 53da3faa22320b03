// SlotStore: free-list slot allocation over structure-of-arrays buffers.
#include "systems/geometry/controller/slot_store.hpp"

#include <algorithm>
#include <cassert>

namespace aloha {

uint32_t SlotStore::acquire() {
    if (free_.empty()) grow(std::max<uint32_t>(4, 2 * capacity_));
    const uint32_t s = free_.back();
    free_.pop_back();
    return s;
}

void SlotStore::reserve(uint32_t slots) {
    if (slots > capacity_) grow(slots);
}

void SlotStore::release(uint32_t slot) {
    assert(slot < capacity_);
    assert(std::find(free_.begin(), free_.end(), slot) == free_.end());
    pending[slot] = 0;
    shows_morph[slot] = 0;
    valid[slot] = 0;
    if (!placed.empty()) placed[slot] = 0;
    frames_left_[slot] = 0;
    free_.push_back(slot);
}

size_t SlotStore::bytes_per_slot() const {
    const SlotLayout& l = layout_;
    return (size_t{l.boxes} + l.palette) * sizeof(glm::mat4) + size_t{l.shapes} * (2 * sizeof(glm::vec3) + sizeof(glm::quat)) +
           size_t{l.muscle_vertices} * 2 * sizeof(glm::vec3) + size_t{l.springs} * 3 * sizeof(glm::vec3) + l.spring_flags +
           (size_t{l.control} + l.morph + l.control_normals + size_t{l.refined} * 2) * sizeof(glm::vec3) +
           2 * sizeof(uint16_t) + 3 * sizeof(uint8_t) + (l.spring_flags ? sizeof(Transform) + sizeof(uint8_t) : 0);
}

void SlotStore::grow(uint32_t new_capacity) {
    assert(new_capacity > capacity_);
    const size_t n = new_capacity;
    const SlotLayout& l = layout_;
    boxes_.resize(n * l.boxes);
    palette_.resize(n * l.palette);
    centres_.resize(n * l.shapes);
    rotations_.resize(n * l.shapes);
    radii_.resize(n * l.shapes);
    muscle_pos_.resize(n * l.muscle_vertices);
    muscle_nrm_.resize(n * l.muscle_vertices);
    spring_end_.resize(n * l.springs);
    spring_vel_.resize(n * l.springs);
    spring_prev_.resize(n * l.springs);
    spring_init_.resize(n * l.spring_flags, 0);
    positions_.resize(n * l.control);
    deltas_.resize(n * l.morph);
    normals_.resize(n * l.control_normals);
    refined_pos_.resize(n * l.refined);
    refined_nrm_.resize(n * l.refined);
    frames_total_.resize(n, 0);
    frames_left_.resize(n, 0);
    pending.resize(n, 0);
    shows_morph.resize(n, 0);
    valid.resize(n, 0);
    placement.resize(l.spring_flags ? n : 0);  // levels with fat springs only
    placed.resize(l.spring_flags ? n : 0, 0);
    // New slots go on the free list so that the lowest index is handed out first.
    for (uint32_t s = new_capacity; s-- > capacity_;) free_.push_back(s);
    capacity_ = new_capacity;
}

}  // namespace aloha
