// Reading GNU build-id notes of loaded objects through the dynamic loader's program headers.
#include "engine/core/build_id.hpp"

#include <elf.h>
#include <link.h>

#include <algorithm>
#include <cstring>

namespace aloha {
namespace {

struct Search {
    uintptr_t address = 0;
    bool found = false;
    LoadedBuildId result;
};

// Size of a note field padded to the notes' 4-byte alignment (ELF gABI).
size_t aligned4(size_t n) { return (n + 3) & ~size_t{3}; }

// The NT_GNU_BUILD_ID descriptor in one PT_NOTE segment of `info`, or empty.
std::vector<uint8_t> build_id_in(const dl_phdr_info* info, const ElfW(Phdr) & note) {
    const auto* p = reinterpret_cast<const uint8_t*>(info->dlpi_addr + note.p_vaddr);
    size_t left = note.p_memsz;
    while (left >= sizeof(ElfW(Nhdr))) {
        ElfW(Nhdr) h;
        std::memcpy(&h, p, sizeof h);
        const size_t name = aligned4(h.n_namesz), desc = aligned4(h.n_descsz);
        if (sizeof h + name + desc > left) break;
        const uint8_t* n = p + sizeof h;
        if (h.n_type == NT_GNU_BUILD_ID && h.n_namesz == 4 && std::memcmp(n, "GNU", 4) == 0)
            return std::vector<uint8_t>(n + name, n + name + h.n_descsz);
        p += sizeof h + name + desc;
        left -= sizeof h + name + desc;
    }
    return {};
}

int visit(dl_phdr_info* info, size_t, void* data) {
    auto* s = static_cast<Search*>(data);
    bool contains = false;
    for (ElfW(Half) i = 0; i < info->dlpi_phnum && !contains; ++i) {
        const ElfW(Phdr)& ph = info->dlpi_phdr[i];
        const uintptr_t begin = info->dlpi_addr + ph.p_vaddr;
        contains = ph.p_type == PT_LOAD && s->address >= begin && s->address - begin < ph.p_memsz;
    }
    if (!contains) return 0;
    s->found = true;
    s->result.object = info->dlpi_name ? info->dlpi_name : "";
    for (ElfW(Half) i = 0; i < info->dlpi_phnum && s->result.id.empty(); ++i)
        if (info->dlpi_phdr[i].p_type == PT_NOTE) s->result.id = build_id_in(info, info->dlpi_phdr[i]);
    return 1;
}

}  // namespace

Result<LoadedBuildId> build_id_of(uintptr_t address) {
    Search s;
    s.address = address;
    dl_iterate_phdr(visit, &s);
    if (!s.found) return make_error("", "no loaded object contains the code address asked for");
    const std::string name = s.result.object.empty() ? "the executable" : s.result.object;
    if (s.result.id.empty())
        return make_error(name, "has no GNU build-id note (linked without --build-id)");
    return s.result;
}

Result<std::vector<uint8_t>> build_ids_of(std::span<const uintptr_t> addresses) {
    std::vector<uint8_t> out;
    std::vector<std::string> seen;
    for (const uintptr_t a : addresses) {
        auto id = build_id_of(a);
        if (!id.ok()) return id.error();
        if (std::find(seen.begin(), seen.end(), id.value().object) != seen.end()) continue;
        seen.push_back(id.value().object);
        out.push_back(static_cast<uint8_t>(id.value().id.size()));
        out.insert(out.end(), id.value().id.begin(), id.value().id.end());
    }
    return out;
}

}  // namespace aloha
