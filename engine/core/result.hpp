// Result-style error values for everything that comes from outside (files, Vulkan, command line).
// Programmer errors use assertions instead; per-frame code never throws.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace aloha {

/// What kind of problem an Error is, for callers that branch on it (retry, ask again, report).
enum class ErrorKind : uint8_t {
    Input = 0,  ///< a file's or text's content is wrong (syntax, schema, values): fix the input
    Io,         ///< a file cannot be found, opened or read (`code` holds errno)
    Option,     ///< a host option is out of range for the data (`path` names the option's field)
    Gpu,        ///< the graphics device refused (`code` holds the VkResult)
};

/// One problem found in an input: which file, where in it (line/column and/or a JSON path),
/// and what is wrong. `code` carries a VkResult or errno when one applies (0 otherwise).
struct Error {
    std::string file;     ///< file the problem is in ("" when not file-based, e.g. Vulkan)
    int line = 0;         ///< 1-based line, 0 when unknown
    int column = 0;       ///< 1-based column, 0 when unknown
    std::string path;     ///< JSON path ("/characters/3/position") or other place, "" when unknown
    std::string message;  ///< what is wrong, in words a user can act on
    int64_t code = 0;     ///< VkResult / errno / other numeric code, 0 when none
    ErrorKind kind = ErrorKind::Input;  ///< what kind of problem (make_error: Input)

    /// Formats as "file:line:column: path: message" leaving out the parts that are unknown.
    [[nodiscard]] std::string to_string() const;
};

/// Builds an Error for `file` at optional `line`/`column` with `message`.
[[nodiscard]] Error make_error(std::string file, std::string message, int line = 0, int column = 0,
                               std::string path = {});

/// Builds an Error of `kind` for `file` with `message` (and `code`: errno, VkResult).
[[nodiscard]] Error make_error(ErrorKind kind, std::string file, std::string message, int64_t code = 0);

/// Builds an ErrorKind::Option error: host option `option` (the options struct's field name) does not
/// fit the data in `file`. Hosts say how the option was set (a command-line flag, a menu).
[[nodiscard]] Error option_error(std::string file, std::string option, std::string message);

/// A value or an Error. Requires T to be movable. Check `ok()` before `value()`.
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : data_(std::move(value)) {}          // NOLINT: implicit by design
    Result(Error error) : data_(std::move(error)) {}      // NOLINT: implicit by design

    /// True when a value is held.
    [[nodiscard]] bool ok() const { return data_.index() == 0; }
    explicit operator bool() const { return ok(); }
    /// The held value; requires ok().
    T& value() & { return std::get<0>(data_); }
    const T& value() const& { return std::get<0>(data_); }
    T&& value() && { return std::get<0>(std::move(data_)); }
    /// The held error; requires !ok().
    [[nodiscard]] const Error& error() const { return std::get<1>(data_); }

private:
    std::variant<T, Error> data_;
};

/// Success or an Error, for operations with no value.
class [[nodiscard]] Status {
public:
    Status() = default;
    Status(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit by design
    /// True on success.
    [[nodiscard]] bool ok() const { return ok_; }
    explicit operator bool() const { return ok_; }
    /// The error; requires !ok().
    [[nodiscard]] const Error& error() const { return error_; }

private:
    Error error_;
    bool ok_ = true;
};

/// Joins several errors into one multi-line message (used by Validate()-style checks).
[[nodiscard]] std::string join_errors(const std::vector<Error>& errors);

/// One Error carrying every problem a loader found: the first, its message followed by
/// "(and N more: ...)" listing the others. Requires a non-empty `errors`.
[[nodiscard]] Error first_and_rest(const std::vector<Error>& errors);

}  // namespace aloha
