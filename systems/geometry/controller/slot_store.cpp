// SlotStore: free-list slot allocation over pages of per-slot records, with a spare page prepared off the frame.
#include "systems/geometry/controller/slot_store.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace aloha {

namespace {

constexpr size_t kPageTarget = size_t{1} << 20;  // about 1 MiB of records per page
constexpr uint32_t kMaxPageShift = 10;           // at most 1,024 slots per page

size_t align_up(size_t n, size_t a) { return (n + a - 1) / a * a; }

// A page of `bytes` whose memory is written once (zeros) so later writes take no page faults.
std::unique_ptr<std::byte[]> touched_page(size_t bytes) {
    std::unique_ptr<std::byte[]> page(new std::byte[bytes]);
    std::memset(page.get(), 0, bytes);
    return page;
}

// touched_page() on a background thread at a lower priority (Linux: nice +10 for this thread), so
// preparing a spare takes little from the frame's own threads yet still finishes on a busy machine.
std::unique_ptr<std::byte[]> touched_page_in_background(size_t bytes) {
#ifdef __linux__
    (void)setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
#endif
    return touched_page(bytes);
}

}  // namespace

SlotStore::SlotStore(const SlotLayout& layout) : layout_(layout) {
    const std::array<std::pair<uint32_t, size_t>, kBufferCount> buffers{{
        {layout.boxes, sizeof(glm::mat4)},         {layout.palette, sizeof(glm::mat4)},
        {layout.shapes, sizeof(glm::vec3)},        {layout.shapes, sizeof(glm::quat)},
        {layout.shapes, sizeof(glm::vec3)},        {layout.muscle_vertices, sizeof(glm::vec3)},
        {layout.muscle_vertices, sizeof(glm::vec3)}, {layout.springs, sizeof(glm::vec3)},
        {layout.springs, sizeof(glm::vec3)},       {layout.springs, sizeof(glm::vec3)},
        {layout.spring_flags, sizeof(uint8_t)},    {layout.control, sizeof(glm::vec3)},
        {layout.morph, sizeof(glm::vec3)},         {layout.control_normals, sizeof(glm::vec3)},
        {layout.refined, sizeof(glm::vec3)},       {layout.refined, sizeof(glm::vec3)},
    }};
    size_t at = 0;
    for (size_t b = 0; b < kBufferCount; ++b) {
        offset_[b] = at;
        count_[b] = buffers[b].first;
        element_bytes_[b] = buffers[b].second;
        at = align_up(at + size_t{buffers[b].first} * buffers[b].second, 16);
    }
    record_bytes_ = align_up(at, 64);  // 0 for a level that keeps no per-character buffers
    while (page_shift_ < kMaxPageShift && (record_bytes_ << page_shift_) < kPageTarget) ++page_shift_;
}

SlotStore::~SlotStore() {
    if (spare_.valid()) spare_.wait();
}

void SlotStore::add_page(Page page) {
    const uint32_t per = slots_per_page();
    pages_.push_back(std::move(page));
    const size_t n = size_t{capacity_} + per;
    frames_total_.resize(n, 0);
    frames_left_.resize(n, 0);
    pending.resize(n, 0);
    shows_morph.resize(n, 0);
    valid.resize(n, 0);
    placement.resize(layout_.spring_flags ? n : 0);  // levels with fat springs only
    placed.resize(layout_.spring_flags ? n : 0, 0);
    // New slots go on the free list so that the lowest index is handed out first.
    for (uint32_t s = capacity_ + per; s-- > capacity_;) free_.push_back(s);
    capacity_ += per;
}

void SlotStore::start_spare() {
    if (spare_.valid()) return;
    spare_ = std::async(std::launch::async, touched_page_in_background, page_bytes());
}

uint32_t SlotStore::acquire() {
    if (free_.empty()) {
        // The spare when one was started (waited for if unfinished: it has had the frames since, and at
        // nice +10 it still runs on a busy machine), so a store never holds more than one page beyond
        // its slots; otherwise a fresh page whose first writes fault in the threads that fill it.
        if (spare_.valid()) add_page(spare_.get());
        else add_page(Page(new std::byte[page_bytes()]));
    }
    const uint32_t s = free_.back();
    free_.pop_back();
    // Low on free slots: prepare the next page off the frame (a store that has needed one page of
    // characters is likely to need another).
    if (free_.size() * 2 < slots_per_page()) start_spare();
    return s;
}

void SlotStore::reserve(uint32_t slots) {
    while (capacity_ < slots) add_page(spare_.valid() ? spare_.get() : touched_page(page_bytes()));
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

size_t SlotStore::flag_bytes() const {
    return 2 * sizeof(uint16_t) + 3 * sizeof(uint8_t) + (layout_.spring_flags ? sizeof(Transform) + sizeof(uint8_t) : 0);
}

size_t SlotStore::bytes_per_slot() const {
    size_t bytes = 0;
    for (size_t b = 0; b < kBufferCount; ++b) bytes += count_[b] * element_bytes_[b];
    return bytes + flag_bytes();
}

size_t SlotStore::allocated_bytes() const {
    return pages_.size() * page_bytes() + size_t{capacity_} * flag_bytes() + spare_bytes();
}

}  // namespace aloha
