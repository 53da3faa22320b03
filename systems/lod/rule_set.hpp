// Live tuning: a holder of the current RuleTable that reloads its file on request or when the file
// changes on disk. A failed reload keeps the previous table; LodState is never reset.
#pragma once

#include "engine/core/result.hpp"
#include "systems/lod/rule_table.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// The rule table in use plus where it came from. Tables are held by shared_ptr so a job running
/// on another thread with the old table keeps it alive while a new one is swapped in.
class RuleSet {
public:
    RuleSet() = default;
    /// Loads `path`; on failure the set stays empty (has_table() false) and the error is returned.
    Status load(const std::string& path);
    /// Re-reads the file given to load(). On success swaps the table in; on failure keeps the old
    /// table and returns the error (with every problem in last_errors()).
    Status reload_from_file();
    /// Reloads when the file's modification time or size changed since the last (attempted) load.
    /// Returns true when a new table was swapped in, false when nothing changed, or the error.
    Result<bool> poll();
    /// Swaps in `table` directly (e.g. edited in the viewer). Requires a valid table.
    void set_table(RuleTable table);

    /// True once a table is loaded.
    [[nodiscard]] bool has_table() const { return table_ != nullptr; }
    /// The current table; requires has_table().
    [[nodiscard]] const RuleTable& table() const { return *table_; }
    /// The current table as a shared pointer (null before the first load).
    [[nodiscard]] std::shared_ptr<const RuleTable> shared() const { return table_; }
    /// Incremented each time a new table is swapped in.
    [[nodiscard]] uint32_t generation() const { return generation_; }
    /// Every problem of the last failed load/reload (empty after a success).
    [[nodiscard]] const std::vector<Error>& last_errors() const { return last_errors_; }
    /// The file path given to load().
    [[nodiscard]] const std::string& path() const { return path_; }

private:
    std::string path_;
    std::shared_ptr<const RuleTable> table_;
    std::vector<Error> last_errors_;
    uint32_t generation_ = 0;
    std::filesystem::file_time_type stamp_{};
    uintmax_t size_ = 0;
};

}  // namespace aloha
